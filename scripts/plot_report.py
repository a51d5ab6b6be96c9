#!/usr/bin/python3
"""Figures and summary.md for a `deepgi report` output directory.

    scripts/plot_report.py [--summary-only] DIR

Reads DIR/report.csv, DIR/report.json, DIR/discrepancy.csv and
DIR/images/*.pfm (written by `deepgi report`), writes DIR/error_vs_ms.png,
DIR/discrepancy.png, DIR/discrepancy_vs_error.png, DIR/images/<scene>.png
(truth, then each AO method's estimate and signed error), from every
estimator's costs DIR/estimators_error_vs_ms.png, from DIR/flicker.csv
DIR/flicker.png, and DIR/summary.md.
Every statement in the summary is computed from the CSV, so re-running the
report rewrites it. --summary-only writes summary.md alone (no figures; it
needs no matplotlib).

The rows of the first AO method in the CSV compare the tap patterns; the
other methods' rows (the image pattern only) are set beside them in the
figure of error against milliseconds and in the section on estimators.
Files are written to a temporary name and renamed, so a reader never sees
half a file.
"""
import json
import os
import sys

from report_plots.data import STUDY_TAPS, Table, read_discrepancy, read_rows
from report_plots.estimators import at_image_cost, estimators_section
from report_plots.figures import (plot_discrepancy, plot_discrepancy_vs_error, plot_error_vs_ms,
                                  plot_images)
from report_plots.summary import summary


def main():
    arguments = sys.argv[1:]
    summary_only = "--summary-only" in arguments
    arguments = [a for a in arguments if a != "--summary-only"]
    if len(arguments) != 1:
        sys.exit("usage: plot_report.py [--summary-only] DIR")
    directory = arguments[0]
    all_rows = read_rows(os.path.join(directory, "report.csv"))
    if not all_rows:
        sys.exit("plot_report: report.csv has no rows")
    # Every estimator at every cost goes to estimators.py; the rest of the
    # report reads the slice estimators at one cost.
    every_cost = all_rows
    all_rows = at_image_cost(all_rows)
    methods = list(dict.fromkeys(r["ao_method"] for r in all_rows))
    # The first method's rows compare the patterns; the rest stand beside them.
    rows = [r for r in all_rows if r["ao_method"] == methods[0]]
    others = [(m, Table([r for r in all_rows if r["ao_method"] == m])) for m in methods[1:]]
    with open(os.path.join(directory, "report.json")) as f:
        info = json.load(f)["info"]
    if summary_only:
        series = read_discrepancy(os.path.join(directory, "discrepancy.csv"))
        summary(directory, rows, info, series, None, all_rows)
        return
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
    summary(directory, rows, info, series, images, all_rows,
            extra=lambda add: estimators_section(plt, directory, every_cost, info, add))


if __name__ == "__main__":
    main()
