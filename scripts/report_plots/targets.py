"""The summary's checks against bounds: the AO estimators against the accuracy
targets of docs/deep-sao.md, and the numerical hard cases (stability.csv,
float_vs_exact.csv). A miss an estimator has by construction is labelled
"expected (by design: why)", never counted as a failure; every other miss is."""
import math
import os

from .data import METHOD_LABELS, PATTERN_LABELS, TARGET_BIAS, TARGET_MAE, fmt, mean, read_csv
from .noise import decide, spread

# Misses an estimator has by construction, by (method, check). The published
# estimator (docs/deep-sao.md) computes AV = 1 - sqrt(pi / N * sum): the
# square root is not the visibility integral, and it turns a small sum s into
# a darkening of sqrt(s) (s = 1e-4 already gives 0.99); its epsilon of
# 1e-4 m^2 (shaders/ao_published.glsl) is an absolute area.
EXPECTED = {
    ("published", "bias"): "1 - sqrt(...) is not the visibility integral; it darkens every "
                           "occluded pixel",
    ("published", "open"): "1 - sqrt(s) turns an occlusion sum of 1e-4 into AV 0.99",
    ("published", "scale"): "its epsilon of 1e-4 m^2 is an absolute area, which scaling the "
                            "scene does not scale",
}


def expected(method, check):
    """The by-design reason for a miss of `check` by `method`, or None."""
    return EXPECTED.get((method, check))


def label(method, check):
    return f"expected (by design: {expected(method, check)})"


STABILITY_FAMILIES = (
    ("scale", "Same scene scaled (every length scaled to match; factors in the case names)"),
    ("far floor", "Open floor 1 km away, 1 mm near plane"),
    ("grazing floor", "Open floor at grazing angles"),
    ("guard-band edge", "Depth discontinuity in the guard band"),
    ("1x1", "1x1 image"),
    ("3x2", "3x2 image"),
)


def family_prefix(case):
    return next((prefix for prefix, _ in STABILITY_FAMILIES if case.startswith(prefix)), case)


def stability_section(directory, add):
    """States the hard cases (stability.csv) and the exact-against-double
    search comparison (float_vs_exact.csv), when the run was asked for them
    (`--stability`, `--float-check`)."""
    cases = read_csv(os.path.join(directory, "stability.csv"))
    choices = read_csv(os.path.join(directory, "float_vs_exact.csv"))
    if cases is None and choices is None:
        return
    add("## Numerical stability\n")
    if cases is not None:
        passing = sum(1 for c in cases if c["pass"] == "1")
        failing = [c for c in cases if c["pass"] != "1"]
        by_design = [c for c in failing if expected(c["ao_method"], family_prefix(c["case"]))]
        add("The hard cases of `tests/runtime/stability_test.cpp`, rendered by the report once "
            "per AO estimator (the tap-gathering ones with the shipped tap pattern): "
            f"**{passing} of {len(cases)} checks pass**"
            + (f"; {len(by_design)} of the {len(failing)} that do not are expected (by design)"
               if by_design else "")
            + ". Worst value per estimator, kind of case and measured quantity (every row is "
            "in `stability.csv`):\n")
        add("| estimator | case | quantity | checks | pass | worst | bound | status |")
        add("|:--|:--|:--|--:|--:|--:|:--|:--|")
        groups = {}
        for c in cases:
            prefix = family_prefix(c["case"])
            family = dict(STABILITY_FAMILIES).get(prefix, c["case"])
            key = (c["ao_method"], prefix, family, c["quantity"], c["test"])
            groups.setdefault(key, []).append(c)
        for (method, prefix, family, quantity, test), members in groups.items():
            values = [float(c["value"]) for c in members]
            if any(math.isnan(v) for v in values):
                worst = float("nan")
            else:
                worst = max(values) if test == "<=" else min(values)
            bounds = sorted({float(c["tolerance"]) for c in members})
            bound = " or ".join(f"{test} {b:g}" for b in bounds)
            good = sum(1 for c in members if c["pass"] == "1")
            status = ("pass" if good == len(members) else
                      label(method, prefix) if expected(method, prefix) else "FAIL")
            add(f"| {METHOD_LABELS.get(method, method)} | {family} | "
                f"{quantity.replace('|', '&#124;')} | {len(members)} | {good} | "
                f"{worst:.4g} | {bound} | {status} |")
        add("")
        for title, chosen in (("Failing checks", [c for c in failing if c not in by_design]),
                              ("Checks missed as expected (by design)", by_design)):
            if not chosen:
                continue
            add(f"{title}:\n")
            for c in chosen:
                add(f"- {c['case']} ({c['ao_method']}): {c['quantity']} = {c['value']} "
                    f"(must be {c['test']} {float(c['tolerance']):g})")
            add("")
        exact = [METHOD_LABELS.get(m, m) for m in dict.fromkeys(c["ao_method"] for c in cases)
                 if all(c["pass"] == "1" for c in cases
                        if c["ao_method"] == m and c["case"].startswith("scale"))]
        if exact:
            add(f"With the {' and the '.join(exact)}, scaling by a power of two changes no raw AV "
                "pixel at all (bound 0); by 1e-3 and 1e3 the largest change is the worst value "
                "above.\n")
    if choices is not None and choices:
        max_n = max(int(c["n"]) for c in choices)
        differing = [c for c in choices if c["differs"] == "1"]
        worse = [c for c in differing if c["exact_tie"] != "1"]
        add(f"**Exact against double-precision tau search** (n = 1..{max_n}, "
            "`float_vs_exact.csv`): a double implementation of the same discrepancy picks a "
            f"different tau than the exact integer search at **{len(differing)}** n"
            + ("." if not differing else
               "; every one of them is another exact minimiser (the same K), so rounding costs "
               "reproducibility, not quality." if not worse else
               f"; {len(worse)} of them have a larger exact K (a worse pattern): "
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
            add("The n up to 128 where they differ: " + (", ".join(shown) or "none")
                + (f"; {rest} more up to {max_n}, every one in `float_vs_exact.csv`." if rest
                   else ".") + "\n")


def _count(value):
    return "-" if value is None else f"{value:.0f}"


def estimator_section(rows, info, add):
    """Every AO method at the image configuration, scene by scene, against
    the ray-traced truth (never against its own converged result, which is
    its own bias), the accuracy targets, and what each costs. Values are
    means over the repeats; open-pixel counts are the worst repeat's."""
    methods = list(dict.fromkeys(r["ao_method"] for r in rows))
    if len(methods) < 2:
        return
    pattern = info.get("image_pattern") or "optimal"
    n = info.get("image_taps")
    layers = sorted({r["layers"] for r in rows})
    top = layers[-1]
    scenes = list(dict.fromkeys(r["scene"] for r in rows))

    # The rows at the image configuration, by method, scene and layer count
    # (one per repeat).
    index = {}
    for r in rows:
        if r["pattern"] == pattern and r["taps"] == n:
            index.setdefault((r["ao_method"], r["scene"], r["layers"]), []).append(r)

    def found_rows(method, scene, layer=top):
        return index.get((method, scene, layer), [])

    def value(method, scene, column, layer=top):
        return mean([r.get(column) for r in found_rows(method, scene, layer)])

    def repeats(method, scene, column, layer=top):
        return [r.get(column) for r in found_rows(method, scene, layer)]

    def worst_count(method, scene, column):
        values = [r.get(column) for r in found_rows(method, scene) if r.get(column) is not None]
        return max(values) if values else None

    add(f"## AO estimators ({PATTERN_LABELS.get(pattern, pattern)}, N = {n}, {top} "
        f"layer{'s' if top > 1 else ''})\n")
    add("Each estimator against the same truth, the ray-traced AV, after the blur, in the first "
        "frame after a cut and after a whole rotation cycle of a still camera (\"cycle\"); no "
        "estimator is compared with its own converged result here, since that result carries "
        "its own bias. Values are means over the run's repeats; \"spread\" is the run-to-run "
        "range of the first frame's MAE. The march casts its own rays "
        "(`DEEPGI_AO_MARCH_RAYS` x `DEEPGI_AO_MARCH_STEPS` samples), so N there is only the "
        "radiosity gather's. \"Open\" pixels have nothing within the AO radius in the truth "
        "(AV >= 0.9999); the last columns count, in the worst repeat, those whose estimate falls "
        "below 0.99 among the open pixels in open surroundings, as the target counts them "
        "(before the blur an open 3x3 neighbourhood, robust to the truth's own noise; after it, "
        "open neighbours within the blur's reach, since next to occluded pixels the blur "
        "rightly averages their occlusion in), and in brackets among all open pixels.\n")
    add("| scene | estimator | SAO ms | MAE | spread | bias | MAE, cycle | bias, cycle | open | "
        "below 0.99: raw / blurred / cycle |")
    add("|:--|:--|--:|--:|--:|--:|--:|--:|--:|:--|")
    for scene in scenes:
        for method in methods:
            if not found_rows(method, scene):
                continue
            add(f"| {scene} | {METHOD_LABELS.get(method, method)} | "
                f"{fmt(value(method, scene, 'sao_ms'), 2)} | "
                f"{fmt(value(method, scene, 'ref_blur_mae'))} | "
                f"{fmt(spread(repeats(method, scene, 'ref_blur_mae')))} | "
                f"{fmt(value(method, scene, 'ref_blur_bias'))} | "
                f"{fmt(value(method, scene, 'ref_accum_mae'))} | "
                f"{fmt(value(method, scene, 'ref_accum_bias'))} | "
                f"{_count(worst_count(method, scene, 'ref_open_pixels'))} | " +
                " / ".join(f"{_count(worst_count(method, scene, f'ref_open_core_{stage}_below'))} "
                           f"({_count(worst_count(method, scene, f'ref_open_{stage}_below'))})"
                           for stage in ("raw", "blur", "accum")) + " |")
    add("")

    # The targets, each per stage: met on how many scenes, which miss, and
    # whether a miss is expected by design.
    add("Against the accuracy targets of docs/deep-sao.md (blurred, "
        f"{top} layer{'s' if top > 1 else ''}; a miss an estimator has by construction is "
        "labelled expected, with the reason):\n")
    add("| estimator | target | first frame: met on | after a cycle: met on | status |")
    add("|:--|:--|:--|:--|:--|")
    for method in methods:
        present = [scene for scene in scenes if found_rows(method, scene)]
        if not present:
            continue
        checks = (
            ("mae", f"MAE <= {TARGET_MAE}", "ref_{}_mae", lambda v: v <= TARGET_MAE, fmt),
            ("bias", f"&#124;bias&#124; <= {TARGET_BIAS}", "ref_{}_bias",
             lambda v: abs(v) <= TARGET_BIAS, lambda v: f"{v:+.4f}"),
            ("open", "no open pixel below 0.99 in open surroundings",
             "ref_open_core_{}_below", lambda v: v == 0, _count),
        )
        for check, title, column, holds, show in checks:
            cells, unexpected, by_design = [], 0, 0
            reasons = set()
            for stage in ("blur", "accum"):
                name = column.format(stage)
                measured = []
                for scene in present:
                    v = (worst_count(method, scene, name) if check == "open"
                         else value(method, scene, name))
                    if v is not None:
                        measured.append((scene, v))
                misses = [(scene, v) for scene, v in measured if not holds(v)]
                for scene, v in misses:
                    why = expected(method, check)
                    if check == "mae":
                        # An MAE miss is the bias's when the bias is most of it.
                        bias = value(method, scene, f"ref_{stage}_bias")
                        why = (expected(method, "bias")
                               if bias is not None and expected(method, "bias")
                               and abs(bias) >= 0.5 * v else None)
                    if why:
                        by_design += 1
                        reasons.add(why if check != "mae" else
                                    "most of the error is its bias, and " + why)
                    else:
                        unexpected += 1
                cells.append(f"{len(measured) - len(misses)} of {len(measured)}" +
                             (f" ({', '.join(f'{scene} {show(v)}' for scene, v in misses)})"
                              if misses else ""))
            if unexpected == 0 and by_design == 0:
                status = "met"
            elif unexpected == 0:
                status = f"expected (by design: {'; '.join(sorted(reasons))})"
            elif by_design == 0:
                status = f"missed ({unexpected})"
            else:
                status = (f"missed ({unexpected}); {by_design} expected (by design: "
                          f"{'; '.join(sorted(reasons))})")
            add(f"| {METHOD_LABELS.get(method, method)} | {title} | {cells[0]} | {cells[1]} | "
                f"{status} |")
    add("")

    first = methods[0]
    base_ms = mean([value(first, scene, "sao_ms") for scene in scenes])
    for method in methods:
        present = [scene for scene in scenes if found_rows(method, scene)]
        if not present:
            continue
        parts = []
        if len(layers) > 1:
            worse, within = [], []
            for scene in present:
                two = repeats(method, scene, "ref_blur_mae")
                one = repeats(method, scene, "ref_blur_mae", layers[0])
                decision = decide({"one": one, "two": two})
                if decision.lowest == "one":
                    worse.append(f"{scene} {fmt(mean(one))} -> {fmt(mean(two))}")
                elif decision.noise is None:
                    within.append(f"{scene} (noise not measured)")
                elif decision.lowest is None:
                    within.append(scene)
            parts.append(f"two layers worse than one beyond the noise (MAE, first frame) on "
                         f"{len(worse)} scene(s)" + (f" ({'; '.join(worse)})" if worse else "")
                         + (f"; within the noise on {', '.join(within)}" if within else ""))
        ms = mean([value(method, scene, "sao_ms") for scene in present])
        cost = f"SAO pass {fmt(ms, 2)} ms, mean over scenes"
        if method != first and ms is not None and base_ms:
            cost += f", {ms / base_ms:.2f}x the {METHOD_LABELS.get(first, first)}'s"
        add(f"- **{METHOD_LABELS.get(method, method)}**: {cost}"
            + (f"; {'; '.join(parts)}" if parts else "") + ".")
    add("")
