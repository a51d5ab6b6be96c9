"""The summary's tie section, from ties.csv: for each tap count of the run
whose D(n, tau) has several exact minimisers, every minimiser and the one the
tie-break picks; and, when the report was given a tie_error_study run's
verdicts (`--ties-from`), the sampling error of the pick's mirror pair (tau,
n - tau: the same spiral reflected) against the best other pair's, their
paired difference, its run-to-run spread and the mirror spread. The study's
rule is the report's: a difference no larger than its noise names no
winner."""
import os
from collections import Counter

from .data import read_csv

WORSE = "pick worse beyond spread"


def tie_section(directory, add):
    rows = read_csv(os.path.join(directory, "ties.csv"))
    if rows is None:
        return
    add("## Ties of the tau table\n")
    judged = [r for r in rows if r["verdict"] != ""]
    in_run = [r for r in rows if r["in_run"] == "1"]
    intro = ("Where several tau reach the minimum of D(n, tau), the tie-break picks one by the "
             "band profile (docs/design.md, 'Ties'); mirror pairs tau, n - tau are the same "
             "spiral reflected. 'ties' lists every minimiser, the pick in bold.")
    if judged:
        repeats = sorted({r["repeats"] for r in judged})
        add(intro + " The sampling columns are a tie_error_study run's (`--ties-from`, "
            f"{' or '.join(repeats)} repeats): the raw solid-angle AV's MAE against its own "
            "converged result for the pick's mirror pair and for the best other pair (each the "
            "mean of its two reflections), their difference averaged over the repeats, the "
            "range of that difference over the repeats (its spread), and the mirror spread: "
            "how far a pair's two reflections lie apart, a difference the tie-break cannot "
            "cause since it cannot choose between reflections. A difference within the larger "
            "of the two names no winner.\n")
    else:
        add(intro + " This run was given no tie_error_study verdicts (`--ties-from`), so it "
            "does not say how the ties sample (docs/optimizer.md, 'Ties').\n")

    def ties_cell(r):
        return ", ".join(f"**{t}**" if t == r["pick"] else t for t in r["ties"].split())

    def stale(r):
        return r["verdict"] != "" and r["study_pick"] != r["pick"]

    if in_run:
        add("| N | D | ties | pick pair MAE | best other pair | other pair MAE | difference | spread "
            "| mirror spread | verdict |")
        add("|--:|--:|:--|--:|--:|--:|--:|--:|--:|:--|")
        for r in in_run:
            d = f"{r['scaled']}/{r['denominator']}"
            if r["verdict"] == "":
                add(f"| {r['n']} | {d} | {ties_cell(r)} | - | - | - | - | - | - | not measured |")
                continue
            verdict = r["verdict"] + (" (of another pick: the study's build picked "
                                      f"{r['study_pick']})" if stale(r) else "")
            other = r["best_other"] if r["best_other"] != "0" else "-"
            add(f"| {r['n']} | {d} | {ties_cell(r)} | {float(r['pick_mae']):.5f} | "
                f"{other} | {float(r['other_mae']):.5f} | "
                f"{float(r['difference']):+.5f} | {float(r['spread']):.5f} | "
                f"{float(r['mirror_spread']):.5f} | {verdict} |")
        add("")
    else:
        add("No tap count of this run has more than one minimiser.\n")
    current = [r for r in judged if not stale(r)]
    if current:
        counts = Counter(r["verdict"] for r in current)
        ns = [int(r["n"]) for r in current]
        text = "; ".join(f"{v}: {c}" for v, c in sorted(counts.items()))
        add(f"- **Over every n the study measured** ({len(current)} tap counts with ties, "
            f"n = {min(ns)}..{max(ns)}): {text}.")
        worse = [r["n"] for r in current if r["verdict"] == WORSE]
        if worse:
            add(f"- **The pick samples worse than another tie beyond the spread** at n = "
                f"{', '.join(worse)}.")
        else:
            add("- **No pick samples worse than another tie beyond the spread.**")
    if any(stale(r) for r in judged):
        add(f"- The study's pick differs from this build's at n = "
            f"{', '.join(r['n'] for r in judged if stale(r))}; those verdicts are not counted.")
    add("")
