#!/usr/bin/python3
"""Plot D*(n) for each family of spirals against the tap count n.

Families: the integer optimum, the fractional optima for m = 2, 4, 8, the
golden-angle spiral (tau = n (2 - phi)) and tau = 1. Every value comes from
spiralgen, so it is the exact discrepancy (the golden one within the error
bound spiralgen states, far below plotting resolution).

    scripts/plot_discrepancy.py SPIRALGEN [--max-n 64] [--out plot.png] [--csv data.csv]
"""
import argparse
import csv
import io
import json
import subprocess
import sys


def run(spiralgen, *args):
    return subprocess.run([spiralgen, *args], check=True, capture_output=True, text=True).stdout


def table(spiralgen, max_n, m):
    text = run(spiralgen, "table", "--max-n", str(max_n), "--format", "csv", "--denominator", str(m))
    return {int(row["n"]): float(row["value"]) for row in csv.DictReader(io.StringIO(text))}


def single(spiralgen, n, *args):
    out = json.loads(run(spiralgen, "discrepancy", "--n", str(n), *args, "--format", "json"))
    return out["exact"]["discrepancy"]["value"] if "exact" in out else out["discrepancy"]["value"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("spiralgen")
    parser.add_argument("--max-n", type=int, default=64)
    parser.add_argument("--out", default="discrepancy_families.png")
    parser.add_argument("--csv", default="")
    args = parser.parse_args()

    ns = list(range(1, args.max_n + 1))
    families = {}
    for m in (1, 2, 4, 8):
        values = table(args.spiralgen, args.max_n, m)
        families["integer optimum" if m == 1 else f"optimum, m = {m}"] = [values[n] for n in ns]
    families["golden angle"] = [single(args.spiralgen, n, "--turns", "golden") for n in ns]
    families["tau = 1"] = [single(args.spiralgen, n, "--tau", "1") for n in ns]

    if args.csv:
        with open(args.csv, "w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(["n", *families])
            for i, n in enumerate(ns):
                writer.writerow([n, *(repr(v[i]) for v in families.values())])

    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        sys.exit("plot_discrepancy: matplotlib is missing (Debian: python3-matplotlib)")
    fig, ax = plt.subplots(figsize=(8, 5))
    for name, values in families.items():
        ax.plot(ns, values, label=name, marker="." if len(ns) <= 64 else None, linewidth=1)
    ax.set_xlabel("taps n")
    ax.set_ylabel("annular-sector discrepancy D")
    ax.set_yscale("log")
    ax.set_title("Exact discrepancy of each spiral family")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)


if __name__ == "__main__":
    main()
