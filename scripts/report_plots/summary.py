"""summary.md: every statement computed from the report's CSV and JSON, for
the configuration that was run. A conclusion the run is too small to draw is
replaced by what it cannot conclude and why; a difference within the run's
own noise (noise.py) is called "within the noise", never a win."""
import os

from .radiosity import radiosity_section
from .reflections import reflection_section
from .ties import tie_section
from .data import (METHOD_LABELS, PATTERN_LABELS, STUDY_TAPS, Table, atomic_write_text, fmt,
                   mean, spearman)
from .noise import decide, spread
from .targets import estimator_section, stability_section

# A rank correlation needs at least this many patterns and study tap counts.
MIN_PATTERNS = 3
MIN_STUDY_TAPS = 2


def label(pattern):
    return PATTERN_LABELS.get(pattern, pattern)


def per_repeat_mean(lists):
    """The per-repeat mean of several quantities' per-repeat values (each
    list in the order of the run's offsets)."""
    lists = [values for values in lists if values]
    if not lists:
        return []
    length = min(len(values) for values in lists)
    return [mean([values[i] for values in lists]) for i in range(length)]


def ranking_text(decision, show=fmt):
    """"X (0.0123; next Y 0.0130, spread 0.0002)" when a lowest is named,
    else what is within the noise, or why nothing could be ranked."""
    if decision.lowest is not None:
        order = sorted(decision.means, key=lambda name: decision.means[name])
        runner = order[1]
        return (f"{label(decision.lowest)} ({show(decision.means[decision.lowest])}; next "
                f"{label(runner)} {show(decision.means[runner])}, spread "
                f"{show(decision.noise)})")
    if decision.noise is None:
        return f"not ranked ({decision.reason})"
    best = decision.means[decision.tied[0]]
    return (f"within the noise ({', '.join(label(p) for p in decision.tied)} lie within "
            f"{show(decision.noise)} of the lowest mean {show(best)})")


def rays_text(rays):
    """The reference's ray budget as the summary states it."""
    if rays == 0:
        return ("rays per pixel until the standard error is below the targets of "
                "`deepgi reference`")
    return f"{rays} rays per pixel"


def stage_means(table, study, pattern, shown="optimal"):
    """The mean error of each stage of the frame (first frame raw and blurred,
    then after a whole rotation cycle of a still camera: the temporal filter's
    history and its blur) of the pattern `shown`, for columns named by
    `pattern`; None when a stage was not measured."""
    stages = (("raw", "first frame raw"), ("blur", "blurred"),
              ("temporal", "after a whole rotation cycle, the temporal history"),
              ("accum", "blurred"))
    parts = []
    for stage, label in stages:
        values = [table.value(pattern.format(stage), shown, n) for n in study]
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
    offsets = sorted({int(r["temporal_offset"]) for r in rows
                      if r.get("temporal_offset") is not None})
    repeats = max(1, len(offsets))
    seeds = sorted({int(r["rotation_seed"]) for r in rows
                    if r.get("rotation_seed") is not None})
    study = [n for n in STUDY_TAPS if n in taps]
    top = layers[-1]
    first = rows[0]["ao_method"]
    first_label = METHOD_LABELS.get(first, first)
    shown = "optimal" if "optimal" in patterns else patterns[0]
    lines = []
    add = lines.append

    def candidates(column, chosen, n=None, layer=None, scene=None):
        return {p: table.repeats(column, p, n, layer, scene) for p in chosen}

    add("# Deep SAO: speed against error\n")
    add(f"{info.get('renderer', '?')}, {info.get('width')}x{info.get('height')} (guard band "
        f"{info.get('guard')} px), reference {rays_text(info.get('rays'))}, converged = "
        f"optimal tau at {info.get('converged_taps')} taps, timing: {info.get('timing')}, "
        f"median of {info.get('frames')} frames. Scenes: {', '.join(scenes)}. "
        f"Every row rendered {repeats} time{'s' if repeats > 1 else ''} (temporal offsets "
        f"{', '.join(str(o) for o in offsets) or 'not recorded'}"
        + (f"; rotation seeds {', '.join(str(r) for r in seeds)}" if seeds else "")
        + "). "
        f"Run time {info.get('seconds', 0):.0f} s.\n")
    add(f"Errors are mean absolute errors of ambient visibility averaged over the scenes and "
        "repeats (the raw solid-angle AV is signed, as the estimator gives it; the blurred AV is "
        "clamped to [0, 1], as compose uses it). 'Against its own converged' compares the "
        f"{first_label} with itself at many taps: that isolates its sampling error, so it "
        "compares the patterns of that one estimator and never estimators with each other (a "
        "converged result keeps its estimator's bias). 'Against the reference' is against the "
        "Embree ray-traced AV (the whole error), the one truth every estimator is compared "
        "with.\n")
    if repeats > 1:
        add("The run measures its own noise: each repeat starts the temporal sequence "
            "elsewhere" + (" and seeds the per-pixel rotation hash anew, so every pixel's "
                           "rotation and step offsets are another realisation, the field of "
                           "per-pixel angles included" if len(seeds) > 1 else
                           ", which adds one angle to every pixel's rotation (the per-pixel "
                           "field of hashed angles is the same in every repeat)") + ". The "
            "'spread' column is the largest run-to-run range (largest minus smallest repeat) "
            "of any pattern's value at that N. Two values differ only when their means differ "
            "by more than the larger of their two spreads; anything less is called within the "
            "noise, and no sentence below names it a winner.\n")
    else:
        add("Each row was rendered once, so the run did not measure its own noise, and the "
            "conclusions below rank nothing (`--repeats 2` or more measures it).\n")

    add(f"## Tables ({first_label}, {top} layer{'s' if top > 1 else ''})\n")
    for column, title in (("sao_ms", "SAO pass (ms)"),
                          ("conv_raw_mae", "MAE against its own converged result (sampling "
                           "error), before the blur"),
                          ("ref_raw_mae", "MAE against the reference, before the blur"),
                          ("ref_blur_mae", "MAE against the reference, after the blur"),
                          ("ref_blur_bias", "Bias against the reference, after the blur"),
                          ("ref_accum_mae", "MAE against the reference, after the blur, still camera "
                           "after a whole rotation cycle"),
                          ("rad_conv_raw_rel_mae", "Radiosity: relative MAE against its own "
                           "converged gather (sampling error), raw"),
                          ("rad_ref_blur_rel_mae", "Radiosity: relative MAE against the reference, "
                           "after the blur"),
                          ("rad_ref_accum_rel_mae", "Radiosity: relative MAE against the reference, "
                           "after the blur, still camera after a whole rotation cycle")):
        if all(table.value(column, p, n, top) is None for p in patterns for n in taps):
            continue
        digits = 2 if column == "sao_ms" else 4
        add(f"**{title}**\n")
        add("| N | " + " | ".join(label(p) for p in patterns) + " | spread |")
        add("|--:|" + "--:|" * (len(patterns) + 1))
        for n in taps:
            spreads = [spread(table.repeats(column, p, n, top)) for p in patterns]
            spreads = [v for v in spreads if v is not None]
            add(f"| {n} | " + " | ".join(fmt(table.value(column, p, n, top), digits)
                                         for p in patterns)
                + f" | {fmt(max(spreads) if spreads else None, digits)} |")
        add("")

    add("## Conclusions\n")
    # 1. Discrepancy as a predictor of image error: a rank correlation over
    # the patterns, at each N where their errors differ beyond the noise.
    verdicts = []  # (what, mean rank correlation)
    near_untested = []  # the errors whose near-optimal patterns are within the noise
    untested = None  # why the run cannot test D* against error
    if len(patterns) < MIN_PATTERNS or len(study) < MIN_STUDY_TAPS:
        untested = (f"a rank correlation needs at least {MIN_PATTERNS} patterns and "
                    f"{MIN_STUDY_TAPS} of the tap counts N = "
                    f"{', '.join(str(n) for n in STUDY_TAPS)}; this run has {len(patterns)} "
                    f"pattern{'s' if len(patterns) != 1 else ''} and "
                    + (f"N = {', '.join(str(n) for n in study)}" if study else "none of them"))
    elif repeats < 2:
        untested = ("with one render per row the run did not measure its noise, so it cannot "
                    "tell the patterns' order from one realisation of the rotation")
    if untested:
        add(f"- **Does lower discrepancy predict lower error?** This run cannot say: {untested}.")
    else:
        for column, what in (("conv_raw_mae", "sampling error (against its own converged, "
                              "before the blur)"),
                             ("ref_blur_mae", "final error (against the reference, after the "
                              "blur)")):
            def correlations(chosen):
                parts, rhos, within = [], [], []
                for n in study:
                    decision = decide(candidates(column, chosen, n))
                    if len(decision.means) < MIN_PATTERNS:
                        parts.append(f"N = {n}: not measured")
                    elif decision.lowest is None and len(decision.tied) == len(decision.means):
                        within.append(n)
                        parts.append(f"N = {n}: every pattern within the noise "
                                     f"({fmt(decision.noise)})")
                    else:
                        names = list(decision.means)
                        rho = spearman([table.value("discrepancy", p, n) for p in names],
                                       [decision.means[p] for p in names])
                        if rho is not None:
                            rhos.append(rho)
                        ties = len(decision.tied)
                        parts.append(f"N = {n}: {fmt(rho, 2)}" +
                                     (f" ({ties} of {len(names)} within the noise of the lowest)"
                                      if ties > 1 else ""))
                return parts, (mean(rhos) if len(rhos) >= MIN_STUDY_TAPS else None), within

            def verdict(average):
                if average >= 0.6:
                    return "yes: the patterns with lower D* have lower error"
                if average >= 0.3:
                    return "only weakly"
                return "no: the ordering by D* does not carry over to the image"

            parts, average, _ = correlations(patterns)
            text = (f"- **Does lower discrepancy predict lower {what}?** " +
                    (f"{verdict(average)} (Spearman rank correlation of D* against error over "
                     f"the {len(patterns)} patterns, errors averaged over scenes, layers and "
                     f"repeats: {'; '.join(parts)}; mean {average:.2f})."
                     if average is not None else
                     f"This run cannot say: the patterns' errors differ beyond the noise at "
                     f"fewer than {MIN_STUDY_TAPS} tap counts ({'; '.join(parts)})."))
            if average is not None:
                verdicts.append((what, average))
            # tau = 1 is far worse than every other pattern in both D* and
            # error, which alone makes the correlation positive; the question
            # that matters is whether D* ranks the good patterns.
            good = [p for p in patterns if p != "tau1"]
            if len(good) < len(patterns) and len(good) < MIN_PATTERNS and average is not None:
                near_untested.append(what.split(" (")[0])
                text += (f" tau = 1 is far worse than the others in both D* and error, so it "
                         f"alone can make this correlation positive; with {len(good)} other "
                         f"pattern{'s' if len(good) != 1 else ''} the run cannot say whether "
                         "D* ranks the good ones.")
            if MIN_PATTERNS <= len(good) < len(patterns):
                good_parts, good_average, within = correlations(good)
                if good_average is not None:
                    text += (f" Without tau = 1, among the {len(good)} patterns whose D* is "
                             f"within a few percent of each other: {'; '.join(good_parts)}; "
                             f"mean {good_average:.2f}"
                             f"{' (D* does not rank them)' if good_average < 0.3 else ''}.")
                    verdicts.append((what + " among the near-optimal patterns", good_average))
                else:
                    near_untested.append(what.split(" (")[0])
                    text += (f" Without tau = 1, D* cannot be tested on the {len(good)} "
                             "near-optimal patterns: their errors lie within the noise at "
                             + (f"N = {', '.join(str(n) for n in within)}" if within else
                                "too many N") + f" ({'; '.join(good_parts)}).")
            add(text)

    # 1b. The discrepancy ranking itself (n = 1..64 from discrepancy.csv):
    # exact values, no noise in them.
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
                 ", ".join(f"{d['golden'][n]:.4f} vs {d[other][n]:.4f}" for n in STUDY_TAPS
                           if n in d[other]) + ")"
                 if below else "") + ".")

    # 2. Lowest error per N, only beyond the noise.
    if len(patterns) < 2:
        add(f"- **Patterns:** only {label(patterns[0])} was run, so no pattern is ranked.")
    else:
        for column, what in (("conv_raw_mae", "sampling error"), ("ref_blur_mae", "final error")):
            best = [f"N = {n}: {ranking_text(decide(candidates(column, patterns, n)))}"
                    for n in study]
            if best:
                add(f"- **Lowest {what} per N:** " + "; ".join(best) + ".")

    # 3. Denominator: integer optimum against the fractional optima.
    fam = [p for p in ("optimal", "m2", "m4", "m8") if p in patterns]
    if len(fam) > 1 and study:
        per_repeat = {p: per_repeat_mean([table.repeats("conv_raw_mae", p, n) for n in study])
                      for p in fam}
        scores = {p: mean(v) for p, v in per_repeat.items()}
        ds = {p: mean([table.value("discrepancy", p, n) for n in study]) for p in fam}
        valid = [v for v in scores.values() if v is not None]
        relative = ((max(valid) - min(valid)) / min(valid)
                    if valid and min(valid) > 0 else float("nan"))
        add("- **Turn denominator m** (mean over N = " + ", ".join(map(str, study)) + "): " +
            "; ".join(f"m = {1 if p == 'optimal' else p[1:]}: sampling MAE {fmt(scores[p])}, "
                      f"D* {fmt(ds[p])}" for p in fam) +
            f". Lowest sampling error: {ranking_text(decide(per_repeat))}. The {len(fam)} differ "
            f"by {100 * relative:.1f}% in error while D* falls "
            f"{100 * (ds[fam[0]] - ds[fam[-1]]) / ds[fam[0]]:.1f}% from the first to the last.")

    # 4. Taps.
    if len(taps) > 1:
        lo, hi = taps[0], taps[-1]
        c_lo, c_hi = table.value("conv_raw_mae", taps=lo), table.value("conv_raw_mae", taps=hi)
        r_lo, r_hi = table.value("ref_blur_mae", taps=lo), table.value("ref_blur_mae", taps=hi)
        b_hi = table.value("ref_blur_bias", taps=hi)
        if None not in (c_lo, c_hi, r_lo, r_hi) and c_hi > 0 and r_hi > 0:
            sampling = decide({lo: table.repeats("conv_raw_mae", taps=lo),
                               hi: table.repeats("conv_raw_mae", taps=hi)})
            final = decide({lo: table.repeats("ref_blur_mae", taps=lo),
                            hi: table.repeats("ref_blur_mae", taps=hi)})

            def fall(decision, a, b):
                if decision.lowest == hi:
                    return f"falls {a / b:.2f}x ({fmt(a)} to {fmt(b)})"
                if decision.lowest == lo:
                    return f"rises beyond the noise ({fmt(a)} to {fmt(b)})"
                if decision.noise is None:
                    return f"goes from {fmt(a)} to {fmt(b)} (noise not measured)"
                return f"goes from {fmt(a)} to {fmt(b)}, within the noise"

            text = (f"- **More taps:** from N = {lo} to N = {hi} the sampling error "
                    f"{fall(sampling, c_lo, c_hi)}, and the error against the reference "
                    f"{fall(final, r_lo, r_hi)}.")
            if b_hi is not None:
                share = abs(b_hi) / r_hi
                text += (f" At N = {hi} the mean bias is {b_hi:+.4f}, {100 * share:.0f}% of the "
                         "MAE" + (", so most of what remains is the estimator's bias, not "
                                  "sampling." if share >= 0.5 else "."))
            add(text)
        t_lo, t_hi = table.value("sao_ms", taps=lo), table.value("sao_ms", taps=hi)
        if t_lo and t_hi:
            # Every pattern runs the same loop over N taps, so at one N the
            # patterns' times differ only by where the taps land in the depth
            # pyramid and by measurement noise, which the repeats measure.
            differences, noise, beyond = [], [], []
            for n in taps:
                decision = decide(candidates("sao_ms", patterns, n))
                times = list(decision.means.values())
                if len(times) > 1:
                    differences.append((max(times) - min(times)) / mean(times))
                if decision.noise is not None and times:
                    noise.append(decision.noise / mean(times))
                    if decision.lowest is not None or len(decision.tied) < len(times):
                        beyond.append(n)
            text = (f"- **Cost:** the SAO pass takes {t_lo:.2f} ms at N = {lo} and {t_hi:.2f} ms "
                    f"at N = {hi} (mean over patterns, scenes, layers and repeats).")
            if differences:
                text += (f" At one N the patterns' times differ by up to "
                         f"{100 * max(differences):.0f}% (max - min over mean)")
                if noise:
                    text += (f", and one pattern's time varies by up to {100 * max(noise):.0f}% "
                             "from repeat to repeat; " +
                             ("every difference between patterns is within that noise." if not beyond
                              else "the patterns differ beyond it at N = "
                              + ", ".join(map(str, beyond)) + ", although a pattern does not change "
                              "the work per tap."))
                else:
                    text += "; the run did not measure its timing noise."
            add(text)

    # 5. Layers, scene by scene, beyond the noise only.
    if len(layers) > 1:
        n = taps[-1]
        worse, better, within = [], [], []
        for scene in scenes:
            one = table.repeats("ref_blur_mae", taps=n, layers=layers[0], scene=scene)
            two = table.repeats("ref_blur_mae", taps=n, layers=layers[-1], scene=scene)
            decision = decide({"one": one, "two": two})
            if len(decision.means) < 2:
                continue
            change = f"{scene} {fmt(decision.means['one'])} -> {fmt(decision.means['two'])}"
            if decision.lowest == "two":
                better.append(change)
            elif decision.lowest == "one":
                worse.append(change)
            else:
                within.append(scene)
        t1 = table.value("sao_ms", layers=layers[0])
        t2 = table.value("sao_ms", layers=layers[-1])
        add(f"- **Two layers against one** (N = {n}, MAE against the reference after the blur): "
            f"better beyond the noise on {len(better)} scene(s) ({'; '.join(better) or 'none'}), "
            f"worse on {len(worse)} ({'; '.join(worse) or 'none'}), "
            + ("within the noise" if repeats > 1 else "not ranked (noise not measured)")
            + f" on {len(within)} ({', '.join(within) or 'none'}). Two layers cost "
            f"{(t2 / t1) if t1 and t2 else float('nan'):.2f}x the SAO time of one.")

    # 6. Radiosity.
    if study and any(table.value("rad_conv_raw_rel_mae", p, n) is not None
                     for p in patterns for n in study):
        if len(patterns) > 1:
            show3 = lambda v: fmt(v, 3)  # noqa: E731
            parts = [f"N = {n}: "
                     f"{ranking_text(decide(candidates('rad_conv_raw_rel_mae', patterns, n)), show3)}"
                     for n in study]
            add("- **Radiosity** (relative MAE of layer-0 irradiance against its own converged "
                "gather, same pattern as the AO): lowest per N: " + "; ".join(parts) + ".")
        truth = [(n, table.value("rad_ref_blur_rel_mae", shown, n),
                  table.value("rad_ref_blur_rel_bias", shown, n)) for n in study]
        truth = [(n, e, b) for n, e, b in truth if e is not None and b is not None]
        if truth:
            add(f"- **Radiosity against the ray-traced one-bounce irradiance** ({label(shown)}, "
                "blurred first frame after a cut, relative to the truth's mean): " +
                "; ".join(f"N = {n}: MAE {fmt(e, 3)}, bias {b:+.3f}" for n, e, b in truth) +
                "." + bias_trend(truth))
            stages = stage_means(table, study, "rad_ref_{}_rel_mae", shown)
            if stages:
                add(f"- **Radiosity by stage** ({label(shown)}, relative MAE against the truth, "
                    f"mean over N = {', '.join(str(n) for n in study)}): " + stages + ".")
        else:
            add("- **Radiosity against the truth:** the reference traced no irradiance, so "
                "those columns are empty.")
    if study:
        stages = stage_means(table, study, "ref_{}_mae", shown)
        add(f"- **AO by stage** ({label(shown)}, MAE against the reference, mean over "
            f"N = {', '.join(str(n) for n in study)}): " + stages + "."
            if stages else "- **AO by stage:** the temporal columns are empty in this run.")

    # 7. Against the paper: only what this run measured beyond its noise.
    against = []
    misses = [f"{what} (mean rank correlation {average:.2f})" for what, average in verdicts
              if average < 0.3]
    if misses:
        against.append("lower D* does not predict lower " + "; nor ".join(misses) +
                       ", so minimising D* is not what makes a spiral good here")
    if "golden" in patterns and "optimal" in patterns:
        losses = [n for n in study
                  if decide({"golden": table.repeats("conv_raw_mae", "golden", n),
                             "optimal": table.repeats("conv_raw_mae", "optimal", n)}).lowest
                  == "golden"]
        if losses:
            against.append("the golden-angle spiral, which no table is needed for, has lower "
                           "sampling error than the optimal tau beyond the noise at N = "
                           + ", ".join(map(str, losses)))
    if len(layers) > 1:
        n = taps[-1]
        decision = decide({"one": table.repeats("ref_blur_mae", taps=n, layers=layers[0]),
                           "two": table.repeats("ref_blur_mae", taps=n, layers=layers[-1])})
        if decision.lowest == "one":
            against.append(f"two layers measure worse than one on average against the "
                           f"ray-traced truth beyond the noise ({fmt(decision.means['one'])} "
                           f"against {fmt(decision.means['two'])} at N = {n})")
    if near_untested:
        against.append("this run cannot say whether D* ranks the near-optimal patterns by "
                       + " or by ".join(near_untested) + " (too few of them, or their errors "
                       "lie within the noise)")
    if untested or not verdicts:
        against.append("this run cannot test the paper's central claim, that lower D* gives "
                       "lower error" + (f" ({untested})" if untested else
                                        " (the patterns' errors are within the noise)"))
    add("- **Against the paper:** " + ("; ".join(against) + "." if against else
                                       "nothing this run measured beyond its noise "
                                       "contradicts it."))
    add("")

    estimator_section(all_rows or rows, info, add)
    radiosity_section(all_rows or rows, add)
    if extra:
        extra(add)  # sections drawn from more than these rows (estimators.py)
    stability_section(directory, add)
    reflection_section(directory, list(dict.fromkeys(r["scene"] for r in all_rows or rows)), add)
    tie_section(directory, add)

    if images is not None:
        add("## Figures\n")
        add("![error against milliseconds](error_vs_ms.png)\n")
        add("![discrepancy of each pattern](discrepancy.png)\n")
        add("![discrepancy against error](discrepancy_vs_error.png)\n")
        for scene, path in images:
            add(f"![{scene}: truth, estimate, signed error]({path})\n")
    atomic_write_text(os.path.join(directory, "summary.md"), "\n".join(lines))
