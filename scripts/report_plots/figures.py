"""The report's figures (matplotlib, drawn with the Agg backend by the caller)."""
import os

from .data import METHOD_LABELS, PATTERN_LABELS, STUDY_TAPS, read_discrepancy, read_pfm


def atomic_savefig(fig, path):
    tmp = f"{path}.tmp{os.getpid()}.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, path)


def plot_error_vs_ms(plt, table, patterns, taps, layers, out, others=()):
    """`others`: (method, Table of its rows) for the AO methods beside the
    first; each is drawn in black, one marker per method."""
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    # Estimators are compared against one truth only: an estimator's own
    # converged result keeps its bias, so against it a biased estimator
    # looks good. The right panel is the sampling error of the first
    # method's patterns, each against that same estimator converged.
    # Two lines per title: on one line the two titles run into each other.
    panels = [("ref_blur_mae", "every estimator against the same truth:\nMAE against the "
               "ray-traced reference (after the blur)", True),
              ("conv_raw_mae", "sampling error of the patterns of one estimator:\nMAE against "
               "its own converged result (before the blur)", False)]
    for ax, (column, title, with_others) in zip(axes, panels):
        for pattern in patterns:
            for layer in layers:
                xs = [table.value("sao_ms", pattern, n, layer) for n in taps]
                ys = [table.value(column, pattern, n, layer) for n in taps]
                points = [(x, y, n) for x, y, n in zip(xs, ys, taps) if x is not None and y is not None]
                if not points:
                    continue
                # Colour says the pattern, the line style the layer count.
                ax.plot([p[0] for p in points], [p[1] for p in points], marker="o",
                        color=f"C{patterns.index(pattern) % 10}",
                        linestyle="-" if layer == 1 else "--",
                        label=f"{PATTERN_LABELS.get(pattern, pattern)}, {layer} layer{'s' if layer > 1 else ''}")
                if pattern == patterns[0] and layer == layers[-1]:
                    for x, y, n in points:
                        ax.annotate(f"N={n}", (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
        for index, (method, other) in enumerate(others if with_others else ()):
            method_taps = sorted({r["taps"] for r in other.rows})
            for layer in layers:
                xs = [other.value("sao_ms", taps=n, layers=layer) for n in method_taps]
                ys = [other.value(column, taps=n, layers=layer) for n in method_taps]
                points = [(x, y) for x, y in zip(xs, ys) if x is not None and y is not None]
                if not points:
                    continue
                ax.plot([p[0] for p in points], [p[1] for p in points], color="black",
                        marker="*^sDPX"[index % 6], markersize=9,
                        linestyle="-" if layer == 1 else "--",
                        label=f"{METHOD_LABELS.get(method, method)}, {layer} layer{'s' if layer > 1 else ''}")
        ax.set_xlabel("deep SAO pass (ms, median, mean over scenes)")
        ax.set_ylabel("mean absolute error of ambient visibility")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(title, fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
    # The left panel has every curve, so its legend serves both, below them.
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=7)
    fig.tight_layout(rect=(0, 0.04 + 0.035 * ((len(labels) + 3) // 4), 1, 1))
    atomic_savefig(fig, out)
    plt.close(fig)


def plot_discrepancy(plt, path, out):
    series = read_discrepancy(path)
    fig, ax = plt.subplots(figsize=(8, 5))
    for pattern, points in series.items():
        ax.plot([p[0] for p in points], [p[1] for p in points], marker=".", linewidth=1,
                label=PATTERN_LABELS.get(pattern, pattern))
    for n in STUDY_TAPS:
        ax.axvline(n, color="grey", alpha=0.3, linewidth=0.8)
    ax.set_xlabel("taps n")
    ax.set_ylabel("annular-sector discrepancy D*(n)")
    ax.set_yscale("log")
    ax.set_title("Exact discrepancy of each tap pattern (grey: N = 8, 11, 16, 32)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    atomic_savefig(fig, out)
    plt.close(fig)
    return series


def plot_discrepancy_vs_error(plt, table, patterns, study, out):
    fig, axes = plt.subplots(1, len(study), figsize=(4 * len(study), 4), squeeze=False)
    for ax, n in zip(axes[0], study):
        for pattern in patterns:
            d = table.value("discrepancy", pattern, n)
            e = table.value("conv_raw_mae", pattern, n)
            if d is None or e is None:
                continue
            ax.scatter([d], [e], label=PATTERN_LABELS.get(pattern, pattern))
        ax.set_title(f"N = {n}")
        ax.set_xlabel("D*(N)")
        ax.set_ylabel("MAE against its own converged (raw)")
        ax.grid(True, alpha=0.3)
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    atomic_savefig(fig, out)
    plt.close(fig)


def plot_images(plt, directory, scenes, methods):
    import numpy as np

    made = []
    for scene in scenes:
        stem = os.path.splitext(os.path.basename(scene))[0]
        stem = "".join(c if c.isalnum() or c == "-" else "-" for c in stem) or "scene"
        truth_path = os.path.join(directory, "images", f"{stem}-truth.pfm")
        estimates = [(m, os.path.join(directory, "images", f"{stem}-estimate-{m}.pfm"))
                     for m in methods]
        estimates = [(m, path) for m, path in estimates if os.path.exists(path)]
        if not (os.path.exists(truth_path) and estimates):
            continue
        truth = read_pfm(truth_path)
        errors = [(m, estimate, estimate - truth)
                  for m, estimate in ((m, read_pfm(path)) for m, path in estimates)]
        # One colour scale for every method's error, so the rows compare.
        spread = np.concatenate([np.abs(e[np.isfinite(e)]) for _, _, e in errors])
        limit = max(0.05, float(np.percentile(spread, 99))) if spread.size else 0.05
        # The truth, then one column per method: its estimate above its error.
        fig, axes = plt.subplots(2, 1 + len(errors), figsize=(4.3 * (1 + len(errors)), 5.4),
                                 squeeze=False)
        panels = [(axes[0][0], truth, "ray-traced AV", "gray", 0, 1)]
        axes[1][0].axis("off")
        for column, (method, estimate, error) in enumerate(errors, start=1):
            label = METHOD_LABELS.get(method, method)
            panels.append((axes[0][column], estimate, f"{label} (blurred)", "gray", 0, 1))
            panels.append((axes[1][column], error, f"{label} - truth", "coolwarm", -limit, limit))
        for ax, image, title, cmap, lo, hi in panels:
            shown = ax.imshow(image, cmap=cmap, vmin=lo, vmax=hi, interpolation="nearest")
            ax.set_title(f"{scene}: {title}", fontsize=9)
            ax.axis("off")
            fig.colorbar(shown, ax=ax, fraction=0.03)
        fig.tight_layout()
        out = os.path.join(directory, "images", f"{stem}.png")
        atomic_savefig(fig, out)
        plt.close(fig)
        made.append((scene, f"images/{stem}.png"))
    return made
