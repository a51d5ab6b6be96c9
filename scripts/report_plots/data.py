"""Reading a `deepgi report` output directory: the CSV rows and JSON info,
PFM images, the statistics the figures and the summary share, and atomic
writes (a reader never sees half a file)."""
import csv
import math
import os

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


def read_pfm(path, all_channels=False):
    """A PFM as a numpy array, row 0 the image's top: its first channel
    (height x width), or every channel (height x width x channels)."""
    import numpy as np

    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        channels = 3 if kind == b"PF" else 1
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    image = data.reshape(height, width, channels)
    if not all_channels:
        image = image[:, :, 0]
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
    """Means of a column over scenes, layers and repeats (each unless given)."""

    def __init__(self, rows):
        self.rows = rows

    def _matching(self, pattern, taps, layers, scene):
        return [r for r in self.rows
                if (pattern is None or r["pattern"] == pattern)
                and (taps is None or r["taps"] == taps)
                and (layers is None or r["layers"] == layers)
                and (scene is None or r["scene"] == scene)]

    def value(self, column, pattern=None, taps=None, layers=None, scene=None):
        return mean([r.get(column) for r in self._matching(pattern, taps, layers, scene)])

    def repeats(self, column, pattern=None, taps=None, layers=None, scene=None):
        """The same mean in each repeat of the run (rows of one temporal
        offset), in the order of the offsets: the values whose spread is the
        run's noise (noise.py). One value for a run of one repeat."""
        groups = {}
        for r in self._matching(pattern, taps, layers, scene):
            groups.setdefault(r.get("temporal_offset"), []).append(r.get(column))
        return [mean(groups[key]) for key in sorted(groups, key=lambda k: -1 if k is None else k)]


def read_csv(path):
    if not os.path.exists(path):
        return None
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def read_discrepancy(path):
    """discrepancy.csv as pattern -> [(n, D*(n))], n ascending."""
    series = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            series.setdefault(row["pattern"], []).append((int(row["n"]), float(row["discrepancy"])))
    return series
