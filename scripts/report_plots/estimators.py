"""Every AO estimator at several costs (error against milliseconds, one curve
per estimator) and each one's frame-to-frame change (flicker.csv): the
figures estimators_error_vs_ms.png and flicker.png and their summary
sections. Every sentence is computed from the CSV files."""
import math
import os

from .data import METHOD_LABELS, PATTERN_LABELS, atomic_write_text, fmt, mean, read_csv
from .noise import spread
from .figures import atomic_savefig

# The renderer's default slice cost (RenderSettings::ao): the slice
# estimators' point in the per-scene tables and images, as the report picks it.
SHIPPED_SLICE_COST = (2, 8)
LABELS = dict(METHOD_LABELS, **{"gtao": "GTAO", "bitmask": "visibility bitmask",
                                "spiral-thick": "thick spiral"})
MARKERS = "os^Dv*<>"


def label(method):
    return LABELS.get(method, method)


def slice_cost(row):
    """(slices, steps) of a slice estimator's row, None for the others."""
    if row.get("ao_slices") is None or row.get("ao_steps") is None:
        return None
    return int(row["ao_slices"]), int(row["ao_steps"])


def image_slice_cost(rows):
    """The slice cost the report's images and tables use: the shipped one if
    the run has it, else the first in the CSV (report_estimators.hpp)."""
    costs = list(dict.fromkeys(c for c in (slice_cost(r) for r in rows) if c is not None))
    if not costs:
        return None
    return SHIPPED_SLICE_COST if SHIPPED_SLICE_COST in costs else costs[0]


def at_image_cost(rows):
    """The rows without the slice estimators' other costs: what the pattern
    tables, the first figure and the estimator table read."""
    cost = image_slice_cost(rows)
    return [r for r in rows if slice_cost(r) is None or slice_cost(r) == cost]


def cost_label(method, key):
    if isinstance(key, tuple):
        return f"{key[0]}x{key[1]}"
    return "own rays" if method == "march" else f"N={key}"


def curves(rows, info):
    """{method: [(ms, mae, bias, key, mae_spread)]} at the image pattern and
    the most layers, each value the mean over the scenes that every point has
    and then over the run's repeats (`temporal_offset`); mae_spread is the
    range of the per-repeat MAE (None with one repeat; noise.py)."""
    pattern = info.get("image_pattern") or "optimal"
    top = max(r["layers"] for r in rows)
    chosen = [r for r in rows if r["layers"] == top and r["pattern"] == pattern]
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    result = {}
    for method in dict.fromkeys(r["ao_method"] for r in chosen):
        own = [r for r in chosen if r["ao_method"] == method]
        keys = {}
        for r in own:
            repeat = r.get("temporal_offset") or 0
            keys.setdefault(slice_cost(r) or r["taps"], {}).setdefault(repeat, {})[r["scene"]] = r
        points = []
        for key, by_repeat in keys.items():
            per_repeat = []
            for by_scene in by_repeat.values():
                if any(s not in by_scene for s in scenes):
                    continue
                per_repeat.append(tuple(mean([by_scene[s][c] for s in scenes])
                                        for c in ("sao_ms", "ref_blur_mae", "ref_blur_bias")))
            per_repeat = [v for v in per_repeat if v[0] is not None and v[1] is not None]
            if not per_repeat:
                continue
            ms = mean([v[0] for v in per_repeat])
            mae = mean([v[1] for v in per_repeat])
            bias = mean([v[2] for v in per_repeat if v[2] is not None])
            points.append((ms, mae, bias, key, spread([v[1] for v in per_repeat])))
        if points:
            # In order of cost (taps, or slices x steps): a curve that turns
            # back in milliseconds shows the timing's noise.
            result[method] = sorted(points, key=lambda p: cost_order(p[3]))
    return result


def cost_order(key):
    return (key[0] * key[1], key[0]) if isinstance(key, tuple) else (key, 0)


def repeat_spread(series):
    """The run's own spread of the curves' error: the largest range of a
    point's MAE over the repeats. None when a point has a single repeat (the
    run did not measure its noise, and nothing is ranked; noise.py)."""
    spreads = [p[4] for points in series.values() for p in points]
    if not spreads or any(v is None for v in spreads):
        return None
    return max(spreads)


def interpolate(points, ms):
    """The curve's MAE at `ms` (linear in log ms between its points taken in
    order of milliseconds), or None outside the costs it was measured at."""
    points = sorted(points, key=lambda p: p[0])
    if ms < points[0][0] or ms > points[-1][0]:
        return None
    for (x0, y0, *_), (x1, y1, *_) in zip(points, points[1:]):
        if x0 <= ms <= x1:
            if x1 == x0:
                return min(y0, y1)
            t = (math.log(ms) - math.log(x0)) / (math.log(x1) - math.log(x0))
            return y0 + t * (y1 - y0)
    return points[0][1] if ms == points[0][0] else None


def equal_cost_findings(series, spread):
    """At every measured cost that two or more curves cover: the most
    accurate estimator, named only where it leads the next by more than the
    spread. Returns one line per run of costs with the same outcome."""
    costs = sorted({p[0] for points in series.values() for p in points})
    outcomes = []
    for ms in costs:
        errors = sorted((e, m) for m, e in ((m, interpolate(p, ms)) for m, p in series.items())
                        if e is not None)
        if len(errors) < 2:
            continue
        (best, winner), (second, runner) = errors[0], errors[1]
        if spread is not None and second - best > spread:
            outcomes.append((ms, ("winner", winner), best, second, runner))
        else:
            outcomes.append((ms, ("tie", winner, runner), best, second, runner))
    lines = []
    i = 0
    while i < len(outcomes):
        j = i
        while j + 1 < len(outcomes) and outcomes[j + 1][1] == outcomes[i][1]:
            j += 1
        lo, hi = outcomes[i][0], outcomes[j][0]
        span = f"at {lo:.2f} ms" if i == j else f"from {lo:.2f} to {hi:.2f} ms"
        lead = min(o[3] - o[2] for o in outcomes[i:j + 1])
        kind = outcomes[i][1]
        runners = list(dict.fromkeys(label(o[4]) for o in outcomes[i:j + 1]))
        if kind[0] == "winner":
            lines.append(f"{span}, the **{label(kind[1])}** is the most accurate: its MAE is at "
                         f"least {lead:.4f} below the next ({' or '.join(runners)}), more than "
                         f"the spread")
        else:
            lines.append(f"{span}, the {label(kind[1])} and the {label(kind[2])} lead within "
                         f"the spread (difference {lead:.4f}): no estimator is named")
        i = j + 1
    return lines


def thick_against_slices(series, spread):
    """The thick spiral's MAE at each measured cost of gtao and the bitmask,
    against theirs: better, worse, or within the spread."""
    thick = series.get("spiral-thick")
    if not thick:
        return []
    lines = []
    for method in ("gtao", "bitmask"):
        for ms, mae, _, key, _ in series.get(method, []):
            own = interpolate(thick, ms)
            if own is None:
                lines.append(f"{label(method)} {cost_label(method, key)} ({ms:.2f} ms, MAE "
                             f"{mae:.4f}): outside the thick spiral's measured costs")
                continue
            if abs(own - mae) <= spread:
                verdict = "within the spread"
            elif own < mae:
                verdict = "the thick spiral is more accurate"
            else:
                verdict = "the thick spiral is less accurate"
            lines.append(f"{label(method)} {cost_label(method, key)} ({ms:.2f} ms): MAE "
                         f"{mae:.4f}, thick spiral {own:.4f}, {verdict}")
    return lines


def plot_estimator_curves(plt, series, out, title):
    fig, ax = plt.subplots(figsize=(8, 5.5))
    for index, (method, points) in enumerate(series.items()):
        ax.plot([p[0] for p in points], [p[1] for p in points], marker=MARKERS[index % len(MARKERS)],
                color=f"C{index % 10}", label=label(method))
        for ms, mae, _, key, _ in points:
            ax.annotate(cost_label(method, key), (ms, mae), textcoords="offset points",
                        xytext=(4, 3), fontsize=7, color=f"C{index % 10}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("deep SAO pass (ms, median over frames, mean over scenes)")
    ax.set_ylabel("MAE against the ray-traced AV (after the blur, first frame)")
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    atomic_savefig(fig, out)
    plt.close(fig)


def number(text):
    return float(text) if text not in ("", None) else None


def flicker_means(flicker):
    """{(method, role): (still, path)} as means over the scenes."""
    result = {}
    for key in dict.fromkeys((f["ao_method"], f["role"]) for f in flicker):
        own = [f for f in flicker if (f["ao_method"], f["role"]) == key]
        result[key] = (mean([number(f["still_change"]) for f in own]),
                       mean([number(f["path_change"]) for f in own]))
    return result


def plot_flicker(plt, flicker, out):
    means = flicker_means(flicker)
    methods = [m for (m, role) in means if role == "estimator"]
    floor = next((v for (m, role), v in means.items() if role == "floor"), (None, None))
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    for ax, index, title in ((axes[0], 0, "still camera, mean over scenes"),
                             (axes[1], 1, "camera path, mean over scenes with a path")):
        values = [means[(m, "estimator")][index] for m in methods]
        ax.bar(range(len(methods)), [v or 0.0 for v in values],
               color=[f"C{i % 10}" for i in range(len(methods))])
        ax.set_xticks(range(len(methods)))
        ax.set_xticklabels([label(m) for m in methods], rotation=25, ha="right", fontsize=8)
        if floor[index] is not None:
            ax.axhline(floor[index], color="black", linestyle="--",
                       label="solid angle at the converged tap count (floor)")
        ax.set_ylabel("mean |AV_t - AV_t-1| per pixel")
        ax.set_title(f"Frame-to-frame change, {title}", fontsize=9)
        ax.grid(True, axis="y", alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, loc="lower center", fontsize=8)
    fig.tight_layout(rect=(0, 0.06 if handles else 0, 1, 1))
    atomic_savefig(fig, out)
    plt.close(fig)


def estimators_section(plt, directory, rows, info, add):
    """Draws both figures into `directory` and adds their sections."""
    series = curves(rows, info)
    if len(series) >= 2:
        pattern = info.get("image_pattern") or "optimal"
        top = max(r["layers"] for r in rows)
        scenes = list(dict.fromkeys(r["scene"] for r in rows))
        plot_estimator_curves(plt, series, os.path.join(directory, "estimators_error_vs_ms.png"),
                              f"{PATTERN_LABELS.get(pattern, pattern)}, {top} layer"
                              f"{'s' if top > 1 else ''}, mean over {len(scenes)} scene"
                              f"{'s' if len(scenes) > 1 else ''}")
        add(f"## Every estimator at several costs ({top} layer{'s' if top > 1 else ''})\n")
        add("Error of the blurred AV against the ray-traced AV in the first frame after a cut, "
            "against the SAO pass's milliseconds, mean over the scenes; the spiral estimators at "
            "each tap count N (the image pattern), gtao and the bitmask at each slices x steps, "
            "the march at its own rays (`estimators_error_vs_ms.png`; columns `sao_ms`, "
            "`ref_blur_mae`, `ref_blur_bias`, `ao_slices`, `ao_steps` of `report.csv`).\n")
        add("| estimator | cost | SAO ms | MAE | bias |")
        add("|:--|:--|--:|--:|--:|")
        for method, points in series.items():
            for ms, mae, bias, key, _ in points:
                add(f"| {label(method)} | {cost_label(method, key)} | {fmt(ms, 2)} | {fmt(mae)} | "
                    f"{fmt(bias)} |")
        add("")
        spread = repeat_spread(series)
        if spread is None:
            add("- **At equal cost:** this run measures no spread (it needs `--repeats` of 2 or "
                "more), so no estimator is named the most accurate.")
        else:
            findings = equal_cost_findings(series, spread)
            add(f"- **Spread:** {spread:.4f}, the largest range of one point's MAE over the "
                "run's repeats (each repeat starts the temporal sequence elsewhere and "
                "seeds the per-pixel rotation anew; docs/report.md, \"Noise\").")
            add("- **At equal cost** (each curve read at the others' measured costs, linearly "
                "in log ms; only where two or more curves reach): " +
                ("; ".join(findings) if findings else "no two curves cover a common cost") + ".")
            against = thick_against_slices(series, spread)
            if against:
                add("- **The thick spiral at the slice estimators' costs** (its curve read at each "
                    "of their points it reaches): " + "; ".join(against) + ".")
        add("")
        add("![every estimator, error against milliseconds](estimators_error_vs_ms.png)\n")
    flicker = read_csv(os.path.join(directory, "flicker.csv"))
    if flicker:
        plot_flicker(plt, flicker, os.path.join(directory, "flicker.png"))
        frames = flicker[0]["frames"]
        half = int(frames) // 2
        add("## Frame-to-frame change\n")
        add(f"Mean |AV_t(p) - AV_t-1(q)| over the viewport's surface pixels, AV the blurred, "
            f"temporally filtered visibility that compose uses, over frames {half + 1} to "
            f"{frames} after a cut (`flicker.csv`, `flicker.png`; docs/report.md defines it). "
            "Still: the default camera, q = p. Path: the scene's camera path from its first "
            "step, q the pixel the motion vector points to, where the previous frame had a "
            "surface there within 5% of p's depth; that change mixes the image's true change "
            "with flicker, so the floor row beside it is the same measure for the solid angle at "
            "the converged tap count, whose own noise is small. Each estimator at the image "
            "configuration; a scene whose path has one key has no path value.\n")
        add("| scene | estimator | still | path |")
        add("|:--|:--|--:|--:|")
        for f in flicker:
            still, path = number(f["still_change"]), number(f["path_change"])
            name = label(f["ao_method"]) + (f" {f['ao_slices']}x{f['ao_steps']}"
                                            if f["ao_slices"] else "")
            if f["role"] == "floor":
                name = f"floor: {label(f['ao_method'])}, N = {f['taps']}"
            add(f"| {f['scene']} | {name} | {fmt(still, 5)} | {fmt(path, 5)} |")
        add("")
        means = flicker_means(flicker)
        ranked = sorted(((v[0], m) for (m, role), v in means.items()
                         if role == "estimator" and v[0] is not None))
        if ranked:
            add("- **Still camera, mean over scenes:** " + ", ".join(
                f"{label(m)} {v:.5f}" for v, m in ranked) + ".")
        ranked = sorted(((v[1], m) for (m, role), v in means.items()
                         if role == "estimator" and v[1] is not None))
        floor = next((v[1] for (m, role), v in means.items() if role == "floor"), None)
        if ranked:
            add("- **Along the path, mean over scenes with a path:** " + ", ".join(
                f"{label(m)} {v:.5f}" for v, m in ranked) +
                (f"; the floor {floor:.5f}" if floor is not None else "") + ".")
            if floor is not None:
                below = [label(m) for v, m in ranked if v < floor]
                if below:
                    add(f"- **Below the floor along the path:** {', '.join(below)} "
                        f"({len(below)} of {len(ranked)}). The floor is not a bound: an estimate "
                        "that varies less over the image, or with the view, than the converged "
                        "solid angle also changes less when the camera moves, so along this path "
                        "the values compare how smooth each estimate is as much as how much it "
                        "flickers; the still camera separates flicker alone.")
                else:
                    add("- **Along the path** every estimator changes more than the floor; the "
                        "excess is its flicker plus whatever its view dependence adds.")
        add("")
        add("![frame-to-frame change per estimator](flicker.png)\n")
