"""summary.md: every statement computed from the report's CSV and JSON."""
import math
import os

from .reflections import reflection_section
from .data import (METHOD_LABELS, PATTERN_LABELS, STUDY_TAPS, TARGET_BIAS, TARGET_MAE, Table,
                   atomic_write_text, fmt, mean, read_csv, spearman)


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


def summary(directory, rows, info, discrepancy_series, images, all_rows=None, extra=None):
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
    if extra:
        extra(add)  # sections drawn from more than these rows (estimators.py)
    stability_section(directory, add)
    reflection_section(directory, list(dict.fromkeys(r["scene"] for r in all_rows or rows)), add)

    add("## Figures\n")
    add("![error against milliseconds](error_vs_ms.png)\n")
    add("![discrepancy of each pattern](discrepancy.png)\n")
    add("![discrepancy against error](discrepancy_vs_error.png)\n")
    for scene, path in images:
        add(f"![{scene}: truth, estimate, signed error]({path})\n")
    atomic_write_text(os.path.join(directory, "summary.md"), "\n".join(lines))
