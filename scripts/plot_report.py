#!/usr/bin/python3
"""Figures and summary.md for a `deepgi report` output directory.

    scripts/plot_report.py DIR

Reads DIR/report.csv, DIR/report.json, DIR/discrepancy.csv and
DIR/images/*.pfm (written by `deepgi report`), writes DIR/error_vs_ms.png,
DIR/discrepancy.png, DIR/discrepancy_vs_error.png, DIR/images/<scene>.png
(truth, then each AO method's estimate and signed error) and DIR/summary.md.
Every statement in the summary is computed from the CSV, so re-running the
report rewrites it.

The rows of the first AO method in the CSV compare the tap patterns; the
other methods' rows (the image pattern only) are set beside them in the
figure of error against milliseconds and in the section on estimators.
Files are written to a temporary name and renamed, so a reader never sees
half a file.
"""
import csv
import json
import math
import os
import sys

PATTERN_LABELS = {
    "optimal": "optimal tau (m = 1)",
    "tau1": "tau = 1",
    "golden": "golden angle",
    "m2": "optimal p/2",
    "m4": "optimal p/4",
    "m8": "optimal p/8",
}
STUDY_TAPS = (8, 11, 16, 32)
METHOD_LABELS = {
    "solid-angle": "solid angle",
    "published": "published 1 - sqrt",
    "march": "march",
}
# The accuracy targets of docs/deep-sao.md for blurred two-layer AV.
TARGET_MAE = 0.03
TARGET_BIAS = 0.01


def atomic_write_text(path, text):
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def atomic_savefig(fig, path):
    tmp = f"{path}.tmp{os.getpid()}.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, path)


def number(text):
    return float(text) if text != "" else None


def read_rows(path):
    with open(path, newline="") as f:
        rows = []
        for raw in csv.DictReader(f):
            row = {"scene": raw["scene"], "pattern": raw["pattern"],
                   "taps": int(raw["taps"]), "layers": int(raw["layers"]),
                   "ao_method": raw.get("ao_method", "solid-angle"),
                   "device": raw.get("device", "")}
            for key, value in raw.items():
                if key not in row:
                    row[key] = number(value)
            rows.append(row)
        return rows


def read_pfm(path):
    import numpy as np

    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        channels = 3 if kind == b"PF" else 1
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    image = data.reshape(height, width, channels)[:, :, 0]
    return np.flipud(image)  # PFM rows run bottom to top


def mean(values):
    values = [v for v in values if v is not None and math.isfinite(v)]
    return sum(values) / len(values) if values else None


def ranks(values):
    order = sorted(range(len(values)), key=lambda i: values[i])
    result = [0.0] * len(values)
    i = 0
    while i < len(order):
        j = i
        while j + 1 < len(order) and values[order[j + 1]] == values[order[i]]:
            j += 1
        for k in range(i, j + 1):
            result[order[k]] = (i + j) / 2.0
        i = j + 1
    return result


def spearman(xs, ys):
    if len(xs) < 3:
        return None
    rx, ry = ranks(xs), ranks(ys)
    mx, my = mean(rx), mean(ry)
    sxy = sum((a - mx) * (b - my) for a, b in zip(rx, ry))
    sxx = sum((a - mx) ** 2 for a in rx)
    syy = sum((b - my) ** 2 for b in ry)
    if sxx == 0 or syy == 0:
        return None
    return sxy / math.sqrt(sxx * syy)


def fmt(value, digits=4):
    return "-" if value is None else f"{value:.{digits}f}"


class Table:
    """Means of a column over scenes (and layers, unless given)."""

    def __init__(self, rows):
        self.rows = rows

    def value(self, column, pattern=None, taps=None, layers=None, scene=None):
        return mean([r[column] for r in self.rows
                     if (pattern is None or r["pattern"] == pattern)
                     and (taps is None or r["taps"] == taps)
                     and (layers is None or r["layers"] == layers)
                     and (scene is None or r["scene"] == scene)])


def plot_error_vs_ms(plt, table, patterns, taps, layers, out, others=()):
    """`others`: (method, Table of its rows) for the AO methods beside the
    first; each is drawn in black, one marker per method."""
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    panels = [("ref_blur_mae", "MAE against the ray-traced reference (after the blur)"),
              ("conv_raw_mae", f"MAE against the converged estimator (before the blur)")]
    for ax, (column, title) in zip(axes, panels):
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
        for index, (method, other) in enumerate(others):
            method_taps = sorted({r["taps"] for r in other.rows})
            for layer in layers:
                xs = [other.value("sao_ms", taps=n, layers=layer) for n in method_taps]
                ys = [other.value(column, taps=n, layers=layer) for n in method_taps]
                points = [(x, y) for x, y in zip(xs, ys) if x is not None and y is not None]
                if not points:
                    continue
                ax.plot([p[0] for p in points], [p[1] for p in points], color="black",
                        marker="*^sD"[index % 4], markersize=9,
                        linestyle="-" if layer == 1 else "--",
                        label=f"{METHOD_LABELS.get(method, method)}, {layer} layer{'s' if layer > 1 else ''}")
        ax.set_xlabel("deep SAO pass (ms, median, mean over scenes)")
        ax.set_ylabel("mean absolute error of ambient visibility")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(title, fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
    # The left panel has every curve (the march has no converged result), so
    # its legend serves both, below them.
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=7)
    fig.tight_layout(rect=(0, 0.04 + 0.035 * ((len(labels) + 3) // 4), 1, 1))
    atomic_savefig(fig, out)
    plt.close(fig)


def plot_discrepancy(plt, path, out):
    series = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            series.setdefault(row["pattern"], []).append((int(row["n"]), float(row["discrepancy"])))
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
        ax.set_ylabel("MAE vs converged (raw)")
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


def read_csv(path):
    if not os.path.exists(path):
        return None
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


# The case families of stability.csv, by the start of the case name.
STABILITY_FAMILIES = (
    ("scale", "Same scene scaled (every length scaled to match; factors in the case names)"),
    ("far floor", "Open floor 1 km away, 1 mm near plane"),
    ("grazing floor", "Open floor at grazing angles"),
    ("guard-band edge", "Depth discontinuity in the guard band"),
    ("1x1", "1x1 image"),
    ("3x2", "3x2 image"),
)


def stability_section(directory, add):
    """States the hard cases (stability.csv) and the exact-against-double
    search comparison (float_vs_exact.csv), when the run measured them."""
    cases = read_csv(os.path.join(directory, "stability.csv"))
    choices = read_csv(os.path.join(directory, "float_vs_exact.csv"))
    if cases is None and choices is None:
        return
    add("## Numerical stability\n")
    if cases is not None:
        passing = sum(1 for c in cases if c["pass"] == "1")
        add("The hard cases of `tests/runtime/stability_test.cpp`, rendered by the report once "
            "per AO estimator (the tap-gathering ones with the shipped tap pattern): "
            f"**{passing} of {len(cases)} checks pass**. Worst value per estimator, kind of case "
            "and measured quantity (every row is in `stability.csv`):\n")
        add("| estimator | case | quantity | checks | pass | worst | bound |")
        add("|:--|:--|:--|--:|--:|--:|:--|")
        groups = {}
        for c in cases:
            family = next((title for prefix, title in STABILITY_FAMILIES
                           if c["case"].startswith(prefix)), c["case"])
            key = (c["ao_method"], family, c["quantity"], c["test"])
            groups.setdefault(key, []).append(c)
        for (method, family, quantity, test), members in groups.items():
            values = [float(c["value"]) for c in members]
            if any(math.isnan(v) for v in values):
                worst = float("nan")
            else:
                worst = max(values) if test == "<=" else min(values)
            bounds = sorted({float(c["tolerance"]) for c in members})
            bound = " or ".join(f"{test} {b:g}" for b in bounds)
            good = sum(1 for c in members if c["pass"] == "1")
            add(f"| {METHOD_LABELS.get(method, method)} | {family} | "
                f"{quantity.replace('|', '&#124;')} | {len(members)} | {good} | "
                f"{worst:.4g} | {bound} |")
        add("")
        failures = [c for c in cases if c["pass"] != "1"]
        if failures:
            add("Failing checks:\n")
            for c in failures:
                add(f"- {c['case']} ({c['ao_method']}): {c['quantity']} = {c['value']} "
                    f"(must be {c['test']} "
                    f"{float(c['tolerance']):g})")
            add("")
        exact = [METHOD_LABELS.get(m, m) for m in dict.fromkeys(c["ao_method"] for c in cases)
                 if all(c["pass"] == "1" for c in cases
                        if c["ao_method"] == m and c["case"].startswith("scale"))]
        if exact:
            add(f"With the {' and the '.join(exact)}, scaling by a power of two changes no raw AV pixel "
                "at all (bound 0); by 1e-3 and 1e3 the largest change is the worst value "
                "above.\n")
    if choices is not None and choices:
        max_n = max(int(c["n"]) for c in choices)
        differing = [c for c in choices if c["differs"] == "1"]
        worse = [c for c in differing if c["exact_tie"] != "1"]
        add(f"**Exact against double-precision tau search** (n = 1..{max_n}, "
            "`float_vs_exact.csv`): a double implementation of the same discrepancy picks a "
            f"different tau than the exact integer search at **{len(differing)}** n; "
            + ("every one of them is another exact minimiser (the same K), so rounding costs "
               "reproducibility, not quality." if not worse else
               f"{len(worse)} of them have a larger exact K (a worse pattern): "
               + ", ".join(c["n"] for c in worse) + ".") + "\n")
        if differing:
            add("| n | exact tau | double tau | exact K | K of double tau | 4n^2 |")
            add("|--:|--:|--:|--:|--:|--:|")
            for c in differing[:8]:
                add(f"| {c['n']} | {c['exact_tau']} | {c['float_tau']} | {c['exact_K']} | "
                    f"{c['float_tau_exact_K']} | {c['denominator']} |")
            add("")
            # Hundreds of n at 1..1024: the first ones show the pattern, the
            # CSV holds every row.
            shown = [c["n"] for c in differing if int(c["n"]) <= 128]
            rest = len(differing) - len(shown)
            add("The n up to 128 where they differ: " + ", ".join(shown)
                + (f"; {rest} more up to {max_n}, every one in `float_vs_exact.csv`." if rest
                   else ".") + "\n")


def estimator_section(rows, info, add):
    """Every AO method at the image configuration, scene by scene, against
    the accuracy targets, and what each costs."""
    methods = list(dict.fromkeys(r["ao_method"] for r in rows))
    if len(methods) < 2:
        return
    pattern = info.get("image_pattern") or "optimal"
    n = info.get("image_taps")
    layers = sorted({r["layers"] for r in rows})
    top = layers[-1]
    scenes = list(dict.fromkeys(r["scene"] for r in rows))

    # The rows at the image configuration, by method, scene and layer count.
    index = {(r["ao_method"], r["scene"], r["layers"]): r for r in rows
             if r["pattern"] == pattern and r["taps"] == n}

    def find(method, scene, layer=top):
        return index.get((method, scene, layer))

    def count(value):
        return "-" if value is None else f"{value:.0f}"

    add(f"## AO estimators ({PATTERN_LABELS.get(pattern, pattern)}, N = {n}, {top} "
        f"layer{'s' if top > 1 else ''})\n")
    add("Each estimator against the ray-traced AV after the blur, in the first frame after a cut "
        "and after a whole rotation cycle of a still camera (\"cycle\"). The march casts its own "
        "rays (`DEEPGI_AO_MARCH_RAYS` x `DEEPGI_AO_MARCH_STEPS` samples), so N there is only the "
        "radiosity gather's. \"Open\" pixels have nothing within the AO radius in the truth "
        "(AV >= 0.9999); the last columns count those whose estimate falls below 0.99 among the "
        "open pixels in open surroundings, as the target counts them (before the blur an open "
        "3x3 neighbourhood, robust to the truth's own noise; after it, open neighbours within "
        "the blur's reach, since next to occluded pixels the blur rightly averages their "
        "occlusion in), and in brackets among all open pixels.\n")
    add("| scene | estimator | SAO ms | MAE | bias | MAE, cycle | bias, cycle | open | "
        "below 0.99: raw / blurred / cycle |")
    add("|:--|:--|--:|--:|--:|--:|--:|--:|:--|")
    for scene in scenes:
        for method in methods:
            r = find(method, scene)
            if r is None:
                continue
            add(f"| {scene} | {METHOD_LABELS.get(method, method)} | {fmt(r['sao_ms'], 2)} | "
                f"{fmt(r['ref_blur_mae'])} | {fmt(r['ref_blur_bias'])} | {fmt(r['ref_accum_mae'])} | "
                f"{fmt(r['ref_accum_bias'])} | {count(r.get('ref_open_pixels'))} | " +
                " / ".join(f"{count(r.get(f'ref_open_core_{stage}_below'))} "
                           f"({count(r.get(f'ref_open_{stage}_below'))})"
                           for stage in ("raw", "blur", "accum")) + " |")
    add("")

    first = methods[0]
    base_ms = mean([r["sao_ms"] for r in (find(first, scene) for scene in scenes) if r])
    for method in methods:
        found = [(scene, find(method, scene)) for scene in scenes]
        found = [(scene, r) for scene, r in found if r is not None]
        if not found:
            continue
        stages = []
        for stage, suffix in (("First frame", "blur"), ("After a cycle", "accum")):
            checks = (
                (f"MAE <= {TARGET_MAE}", f"ref_{suffix}_mae", lambda v: v <= TARGET_MAE, fmt),
                (f"|bias| <= {TARGET_BIAS}", f"ref_{suffix}_bias",
                 lambda v: abs(v) <= TARGET_BIAS, lambda v: f"{v:+.4f}"),
                ("no open pixel below 0.99 in open surroundings", f"ref_open_core_{suffix}_below",
                 lambda v: v == 0,
                 count),
            )
            parts = []
            for label, column, holds, show in checks:
                values = [(scene, r.get(column)) for scene, r in found]
                values = [(scene, v) for scene, v in values if v is not None]
                misses = [f"{scene} {show(v)}" for scene, v in values if not holds(v)]
                parts.append(f"{label} on {len(values) - len(misses)} of {len(values)}"
                             + (f" ({', '.join(misses)})" if misses else ""))
            stages.append(f"{stage}: " + "; ".join(parts))
        worse = []
        if len(layers) > 1:
            for scene, r in found:
                one = find(method, scene, layers[0])
                if one is not None and r["ref_blur_mae"] is not None and \
                        one["ref_blur_mae"] is not None and r["ref_blur_mae"] > one["ref_blur_mae"]:
                    worse.append(f"{scene} {fmt(one['ref_blur_mae'])} -> {fmt(r['ref_blur_mae'])}")
            stages.append(f"Two layers worse than one (MAE, first frame) on "
                          f"{len(worse)} scene(s)" + (f" ({'; '.join(worse)})" if worse else ""))
        ms = mean([r["sao_ms"] for _, r in found])
        cost = f"SAO pass {fmt(ms, 2)} ms, mean over scenes"
        if method != first and ms is not None and base_ms:
            cost += f", {ms / base_ms:.2f}x the {METHOD_LABELS.get(first, first)}'s"
        add(f"- **{METHOD_LABELS.get(method, method)}** ({cost}): " + ". ".join(stages) + ".")
    add("")


def rays_text(rays):
    """The reference's ray budget as the summary states it."""
    if rays == 0:
        return ("rays per pixel until the standard error is below the targets of "
                "`deepgi reference`")
    return f"{rays} rays per pixel"


def stage_means(table, study, pattern):
    """The mean error of each stage of the frame (first frame raw and blurred,
    then after a whole rotation cycle of a still camera: the temporal filter's
    history and its blur), for columns named by `pattern`; None when the
    temporal stage was not measured."""
    stages = (("raw", "first frame raw"), ("blur", "blurred"),
              ("temporal", "after a whole rotation cycle, the temporal history"),
              ("accum", "blurred"))
    parts = []
    for stage, label in stages:
        values = [table.value(pattern.format(stage), "optimal", n) for n in study]
        values = [v for v in values if v is not None]
        if not values:
            return None
        parts.append(f"{label} {fmt(sum(values) / len(values))}")
    return ", ".join(parts)


def bias_trend(truth):
    """What the radiosity bias does as N grows, from the first and last N."""
    if len(truth) < 2:
        return ""
    (n0, _, b0), (n1, _, b1) = truth[0], truth[-1]
    if abs(b1) >= 0.8 * abs(b0):
        return (f" The bias does not shrink with N ({b0:+.3f} at N = {n0}, {b1:+.3f} at "
                f"N = {n1}): it is the gather's (its estimator, or surfaces the G-buffer does "
                "not hold), not the sampling's.")
    return (f" The bias shrinks with N ({b0:+.3f} at N = {n0}, {b1:+.3f} at N = {n1}): part "
            "of it is sampling.")


def summary(directory, rows, info, discrepancy_series, images, all_rows=None):
    table = Table(rows)
    patterns = list(dict.fromkeys(r["pattern"] for r in rows))
    taps = sorted({r["taps"] for r in rows})
    layers = sorted({r["layers"] for r in rows})
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    study = [n for n in STUDY_TAPS if n in taps]
    top = layers[-1]
    lines = []
    add = lines.append
    add("# Deep SAO: speed against error\n")
    add(f"{info.get('renderer', '?')}, {info.get('width')}x{info.get('height')} (guard band "
        f"{info.get('guard')} px), reference {rays_text(info.get('rays'))}, converged = "
        f"optimal tau at {info.get('converged_taps')} taps, timing: {info.get('timing')}, "
        f"median of {info.get('frames')} frames. Scenes: {', '.join(scenes)}. "
        f"Run time {info.get('seconds', 0):.0f} s.\n")
    add("Errors are mean absolute errors of ambient visibility averaged over the scenes (the "
        "raw solid-angle AV is signed, as the estimator gives it; the blurred AV is clamped to "
        "[0, 1], as compose uses it); 'converged' is the same estimator at many taps (isolates the sampling error), "
        "'reference' is the Embree ray-traced AV (the whole error).\n")

    add(f"## Tables ({top} layer{'s' if top > 1 else ''})\n")
    for column, title in (("sao_ms", "SAO pass (ms)"),
                          ("conv_raw_mae", "MAE against converged, before the blur"),
                          ("ref_raw_mae", "MAE against the reference, before the blur"),
                          ("ref_blur_mae", "MAE against the reference, after the blur"),
                          ("ref_blur_bias", "Bias against the reference, after the blur"),
                          ("ref_accum_mae", "MAE against the reference, after the blur, still camera "
                           "after a whole rotation cycle"),
                          ("rad_conv_raw_rel_mae", "Radiosity: relative MAE against converged, raw"),
                          ("rad_ref_blur_rel_mae", "Radiosity: relative MAE against the reference, "
                           "after the blur"),
                          ("rad_ref_accum_rel_mae", "Radiosity: relative MAE against the reference, "
                           "after the blur, still camera after a whole rotation cycle")):
        if all(table.value(column, p, n, top) is None for p in patterns for n in taps):
            continue
        add(f"**{title}**\n")
        add("| N | " + " | ".join(PATTERN_LABELS.get(p, p) for p in patterns) + " |")
        add("|--:|" + "--:|" * len(patterns))
        for n in taps:
            digits = 2 if column == "sao_ms" else 4
            add(f"| {n} | " + " | ".join(fmt(table.value(column, p, n, top), digits) for p in patterns) + " |")
        add("")

    add("## Conclusions\n")
    # 1. Discrepancy as a predictor of image error.
    verdicts = []
    for column, what in (("conv_raw_mae", "sampling error (against converged, before the blur)"),
                         ("ref_blur_mae", "final error (against the reference, after the blur)")):
        def correlations(chosen):
            parts, rhos = [], []
            for n in study:
                ds = [table.value("discrepancy", p, n) for p in chosen]
                es = [table.value(column, p, n) for p in chosen]
                pairs = [(d, e) for d, e in zip(ds, es) if d is not None and e is not None]
                rho = spearman([p[0] for p in pairs], [p[1] for p in pairs])
                if rho is not None:
                    rhos.append(rho)
                parts.append(f"N = {n}: {fmt(rho, 2)}")
            return parts, mean(rhos)

        parts, average = correlations(patterns)
        # tau = 1 is far worse than every other pattern in both D* and error,
        # which alone makes the correlation positive; the question that
        # matters is whether D* ranks the good patterns.
        good = [p for p in patterns if p != "tau1"]
        good_parts, good_average = correlations(good) if len(good) >= 3 and len(good) < len(patterns) else ([], None)
        verdicts.append((what, average))
        if average is None:
            continue
        if average >= 0.6:
            verdict = "yes: the patterns with lower D* have lower error"
        elif average >= 0.3:
            verdict = "only weakly"
        else:
            verdict = "no: the ordering by D* does not carry over to the image"
        add(f"- **Does lower discrepancy predict lower {what}?** {verdict} (Spearman rank "
            f"correlation of D* against error over the {len(patterns)} patterns, mean over scenes "
            f"and layers: {'; '.join(parts)}; mean {average:.2f})." +
            (f" Without tau = 1, among the {len(good)} patterns whose D* is within a few percent "
             f"of each other: {'; '.join(good_parts)}; mean {good_average:.2f}"
             f"{' (D* does not rank them)' if good_average < 0.3 else ''}."
             if good_average is not None else ""))
        if good_average is not None:
            verdicts.append((what + " among the near-optimal patterns", good_average))

    # 1b. The discrepancy ranking itself (n = 1..64 from discrepancy.csv).
    d = {name: dict(points) for name, points in discrepancy_series.items()}
    if "golden" in d:
        for other in ("optimal", "m8"):
            if other not in d:
                continue
            ns = sorted(set(d["golden"]) & set(d[other]))
            below = [n for n in ns if d["golden"][n] < d[other][n] * (1 - 1e-12)]
            add(f"- **Golden angle against {PATTERN_LABELS[other]} in D\\*:** lower at "
                f"{len(below)} of n = 1..{ns[-1]}" +
                (f" (from n = {min(below)}; at N = 8, 11, 16, 32: " +
                 ", ".join(f"{d['golden'][n]:.4f} vs {d[other][n]:.4f}" for n in STUDY_TAPS if n in d[other]) + ")"
                 if below else "") + ".")

    # 2. Best pattern per N.
    for column, what in (("conv_raw_mae", "sampling error"), ("ref_blur_mae", "final error")):
        best = []
        for n in study:
            scored = [(table.value(column, p, n), p) for p in patterns if table.value(column, p, n) is not None]
            if scored:
                e, p = min(scored)
                opt = table.value(column, "optimal", n)
                rel = f", optimal tau {fmt(opt)}" if opt is not None and p != "optimal" else ""
                best.append(f"N = {n}: {PATTERN_LABELS.get(p, p)} ({fmt(e)}{rel})")
        if best:
            add(f"- **Lowest {what} per N:** " + "; ".join(best) + ".")

    # 3. Denominator: integer optimum against the fractional optima.
    fam = [p for p in ("optimal", "m2", "m4", "m8") if p in patterns]
    if len(fam) > 1 and study:
        scores = {p: mean([table.value("conv_raw_mae", p, n) for n in study]) for p in fam}
        ds = {p: mean([table.value("discrepancy", p, n) for n in study]) for p in fam}
        order = sorted(fam, key=lambda p: scores[p] if scores[p] is not None else 1e9)
        valid = [v for v in scores.values() if v is not None]
        spread = (max(valid) - min(valid)) / min(valid) if valid and min(valid) > 0 else float("nan")
        add("- **Turn denominator m** (mean over N = " + ", ".join(map(str, study)) + "): " +
            "; ".join(f"m = {1 if p == 'optimal' else p[1:]}: sampling MAE {fmt(scores[p])}, D* {fmt(ds[p])}"
                      for p in fam) + f". Lowest error: {PATTERN_LABELS.get(order[0], order[0])}, but "
            f"the four differ by {100 * spread:.1f}% in error while D* falls "
            f"{100 * (ds[fam[0]] - ds[fam[-1]]) / ds[fam[0]]:.1f}% from the first to the last.")

    # 4. Taps.
    if len(taps) > 1:
        lo, hi = taps[0], taps[-1]
        c_lo, c_hi = table.value("conv_raw_mae", taps=lo), table.value("conv_raw_mae", taps=hi)
        r_lo, r_hi = table.value("ref_blur_mae", taps=lo), table.value("ref_blur_mae", taps=hi)
        b_hi = table.value("ref_blur_bias", taps=hi)
        if None not in (c_lo, c_hi, r_lo, r_hi):
            add(f"- **More taps:** from N = {lo} to N = {hi} the sampling error falls "
                f"{c_lo / c_hi:.1f}x ({fmt(c_lo)} to {fmt(c_hi)}), but the error against the reference "
                f"only {r_lo / r_hi:.2f}x ({fmt(r_lo)} to {fmt(r_hi)}); at N = {hi} the mean bias is "
                f"{fmt(b_hi)}, so the remaining error is the estimator's, not the sampling's.")
        t_lo, t_hi = table.value("sao_ms", taps=lo), table.value("sao_ms", taps=hi)
        if t_lo and t_hi:
            # Every pattern runs the same loop over N taps, so at one N the
            # patterns' times differ only by where the taps land in the
            # depth pyramid and by measurement noise.
            spreads = []
            for n in taps:
                times = [table.value("sao_ms", p, n) for p in patterns]
                times = [t for t in times if t is not None]
                if len(times) > 1:
                    spreads.append((max(times) - min(times)) / mean(times))
            spread = f" At one N the patterns' times differ by up to {100 * max(spreads):.0f}% " \
                     f"(max - min over mean); a pattern does not change the work per tap, so read " \
                     f"that as timing noise." if spreads else ""
            add(f"- **Cost:** the SAO pass takes {t_lo:.2f} ms at N = {lo} and {t_hi:.2f} ms at "
                f"N = {hi} (mean over patterns, scenes, layers).{spread}")

    # 5. Layers.
    if len(layers) > 1:
        n = taps[-1]
        worse, better, same = [], [], []
        for scene in scenes:
            one = table.value("ref_blur_mae", taps=n, layers=layers[0], scene=scene)
            two = table.value("ref_blur_mae", taps=n, layers=layers[-1], scene=scene)
            if one is None or two is None:
                continue
            # Equal at the four decimals shown counts as equal.
            if round(two, 4) == round(one, 4):
                same.append(scene)
            else:
                (worse if two > one else better).append(f"{scene} {fmt(one)} -> {fmt(two)}")
        t1 = table.value("sao_ms", layers=layers[0])
        t2 = table.value("sao_ms", layers=layers[-1])
        add(f"- **Two layers against one** (N = {n}, MAE against the reference after the blur): "
            f"better on {len(better)} scene(s) ({'; '.join(better) or 'none'}), equal on "
            f"{len(same)} ({', '.join(same) or 'none'}), worse on "
            f"{len(worse)} ({'; '.join(worse) or 'none'}). Two layers cost "
            f"{(t2 / t1) if t1 and t2 else float('nan'):.2f}x the SAO time of one.")

    # 6. Radiosity.
    if study and any(table.value("rad_conv_raw_rel_mae", p, n) is not None for p in patterns for n in study):
        parts = []
        for n in study:
            scored = [(table.value("rad_conv_raw_rel_mae", p, n), p) for p in patterns
                      if table.value("rad_conv_raw_rel_mae", p, n) is not None]
            e, p = min(scored)
            parts.append(f"N = {n}: {PATTERN_LABELS.get(p, p)} ({fmt(e, 3)}; optimal tau "
                         f"{fmt(table.value('rad_conv_raw_rel_mae', 'optimal', n), 3)})")
        add("- **Radiosity** (relative MAE of layer-0 irradiance against its own converged gather, "
            "same pattern as the AO): lowest per N: " + "; ".join(parts) + ".")
        truth = [(n, table.value("rad_ref_blur_rel_mae", "optimal", n),
                  table.value("rad_ref_blur_rel_bias", "optimal", n)) for n in study]
        truth = [(n, e, b) for n, e, b in truth if e is not None and b is not None]
        if truth:
            add("- **Radiosity against the ray-traced one-bounce irradiance** (optimal tau, blurred "
                "first frame after a cut, relative to the truth's mean): " +
                "; ".join(f"N = {n}: MAE {fmt(e, 3)}, bias {b:+.3f}" for n, e, b in truth) +
                "." + bias_trend(truth))
            stages = stage_means(table, study, "rad_ref_{}_rel_mae")
            if stages:
                add("- **Radiosity by stage** (optimal tau, relative MAE against the truth, mean "
                    f"over N = {', '.join(str(n) for n in study)}): " + stages + ".")
        else:
            add("- **Radiosity against the truth:** the reference traced no irradiance, so "
                "those columns are empty.")
    stages = stage_means(table, study, "ref_{}_mae") if study else None
    if stages:
        add("- **AO by stage** (optimal tau, MAE against the reference, mean over "
            f"N = {', '.join(str(n) for n in study)}): " + stages + ".")
    else:
        add("- **Temporal accumulation:** this build has no temporal AO output, so those columns are empty.")

    # 7. Against the paper.
    against = []
    misses = [f"{what} (mean rank correlation {average:.2f})" for what, average in verdicts
              if average is not None and average < 0.3]
    if misses:
        against.append("lower D* does not predict lower " + "; nor ".join(misses) +
                       ", so minimising D* is not what makes a spiral good here")
    if study:
        losses = [n for n in study
                  if table.value("conv_raw_mae", "golden", n) is not None
                  and table.value("conv_raw_mae", "optimal", n) is not None
                  and table.value("conv_raw_mae", "golden", n) < table.value("conv_raw_mae", "optimal", n)]
        if losses:
            against.append("the golden-angle spiral, which no table is needed for, has lower sampling "
                           "error than the optimal tau at N = " + ", ".join(map(str, losses)))
    if len(layers) > 1:
        n = taps[-1]
        one = table.value("ref_blur_mae", taps=n, layers=layers[0])
        two = table.value("ref_blur_mae", taps=n, layers=layers[-1])
        if one is not None and two is not None and two > one:
            against.append(f"two layers measure worse than one on average against the ray-traced truth "
                           f"({fmt(one)} against {fmt(two)} at N = {n})")
    add("- **Against the paper:** " + ("; ".join(against) + "." if against else
                                       "nothing in this run contradicts it."))
    add("")

    estimator_section(all_rows or rows, info, add)
    stability_section(directory, add)

    add("## Figures\n")
    add("![error against milliseconds](error_vs_ms.png)\n")
    add("![discrepancy of each pattern](discrepancy.png)\n")
    add("![discrepancy against error](discrepancy_vs_error.png)\n")
    for scene, path in images:
        add(f"![{scene}: truth, estimate, signed error]({path})\n")
    atomic_write_text(os.path.join(directory, "summary.md"), "\n".join(lines))


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: plot_report.py DIR")
    directory = sys.argv[1]
    all_rows = read_rows(os.path.join(directory, "report.csv"))
    if not all_rows:
        sys.exit("plot_report: report.csv has no rows")
    methods = list(dict.fromkeys(r["ao_method"] for r in all_rows))
    # The first method's rows compare the patterns; the rest stand beside them.
    rows = [r for r in all_rows if r["ao_method"] == methods[0]]
    others = [(m, Table([r for r in all_rows if r["ao_method"] == m])) for m in methods[1:]]
    with open(os.path.join(directory, "report.json")) as f:
        info = json.load(f)["info"]
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        sys.exit("plot_report: matplotlib is missing (Debian: python3-matplotlib)")
    table = Table(rows)
    patterns = list(dict.fromkeys(r["pattern"] for r in rows))
    taps = sorted({r["taps"] for r in rows})
    layers = sorted({r["layers"] for r in rows})
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    plot_error_vs_ms(plt, table, patterns, taps, layers, os.path.join(directory, "error_vs_ms.png"),
                     others)
    series = plot_discrepancy(plt, os.path.join(directory, "discrepancy.csv"),
                              os.path.join(directory, "discrepancy.png"))
    study = [n for n in STUDY_TAPS if n in taps] or taps
    plot_discrepancy_vs_error(plt, table, patterns, study,
                              os.path.join(directory, "discrepancy_vs_error.png"))
    images = plot_images(plt, directory, scenes, methods)
    summary(directory, rows, info, series, images, all_rows)


if __name__ == "__main__":
    main()
