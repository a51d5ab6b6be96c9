"""The summary's per-scene radiosity section: the blurred layer-0 irradiance
against the whole ray-traced truth and against the visible truth (the light
whose source a G-buffer layer of the row holds), and the share of the truth
no layer holds (docs/radiosity.md, "Against the light the layers hold")."""
from .data import Table, fmt

# The one-bounce targets of docs/radiosity.md against the visible truth.
TARGET_MAE = 0.10
TARGET_BIAS = 0.05
# The renderer's default radiosity tap count (the CMake option
# RADIOSITY_TAPS): the section shows the run's tap count nearest it.
DEFAULT_TAPS = 19


def _signed(value):
    return "-" if value is None else f"{value:+.3f}"


def radiosity_section(rows, add):
    rows = [r for r in rows if r.get("rad_vis_accum_rel_mae") is not None]
    if not rows:
        return
    # The still run (`deepgi report --radiosity-frames`), where the run made
    # it: its rows are the configuration to show, and its frames average out
    # most of the gather's noise. Without it, the rows after the cycle.
    still = [r for r in rows if r.get("rad_vis_still_rel_mae") is not None]
    if still:
        rows = still
        frames = int(rows[0]["rad_still_frames"])
        after, stage = f"after {frames} still frames", "still"
    else:
        after, stage = "after the cycle", "accum"
    # Radiosity does not depend on the AO method: one method's rows.
    method = rows[0]["ao_method"]
    patterns = list(dict.fromkeys(r["pattern"] for r in rows if r["ao_method"] == method))
    pattern = "optimal" if "optimal" in patterns else patterns[0]
    rows = [r for r in rows if r["ao_method"] == method and r["pattern"] == pattern]
    taps = min(sorted({r["taps"] for r in rows}), key=lambda n: abs(n - DEFAULT_TAPS))
    table = Table(rows)
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    layers = sorted({r["layers"] for r in rows})
    add("## Radiosity against the whole and the visible truth\n")
    if still:
        noise = (f"a still camera's running mean of {frames} frames leaves little of the "
                 "gather's noise in the MAE.\n")
    else:
        noise = ("a few still frames keep some of the gather's noise in the MAE, which the "
                 "documents' figures average over more frames.\n")
    add(f"The blurred layer-0 irradiance (one bounce, N = {taps}, the pattern {pattern}; "
        "'radius': the radiosity radius the row and its truth used, in scene units), "
        f"relative to the truth's mean over the compared pixels, in the first frame after a "
        f"cut and {after}, means over the repeats. The "
        "whole truth is the ray-traced one-bounce irradiance; the visible truth is its part "
        "whose source surface a layer of the row holds (layer 0 with one layer, layers 0 and "
        "1 with two), the most the gather can find. 'No layer holds': the share of the whole "
        "truth's mean that is not visible. Targets against the visible truth: relative MAE "
        f"<= {TARGET_MAE:.2f} and |bias| <= {TARGET_BIAS:.2f} (docs/radiosity.md); "
        + noise)
    add(f"| scene | radius | layers | no layer holds | whole, first frame | whole, {after} | "
        f"visible, first frame | visible, {after} | targets (visible, {after}) |")
    add("|:--|--:|--:|--:|--:|--:|--:|--:|:--|")
    met, missed = [], []
    for scene in scenes:
        for layer in layers:
            def value(column):
                return table.value(column, taps=taps, layers=layer, scene=scene)

            def pair(prefix):
                return f"{fmt(value(prefix + '_mae'), 3)} / {_signed(value(prefix + '_bias'))}"

            mae = value(f"rad_vis_{stage}_rel_mae")
            bias = value(f"rad_vis_{stage}_rel_bias")
            if mae is None or bias is None:
                continue  # this layer count did not run on this scene
            fails = []
            if mae > TARGET_MAE:
                fails.append("MAE")
            if abs(bias) > TARGET_BIAS:
                fails.append("bias")
            verdict = "met" if not fails else "missed (" + ", ".join(fails) + ")"
            (missed if fails else met).append(f"{scene} ({layer})")
            share, radius = value("rad_unheld_share"), value("radiosity_radius")
            add(f"| {scene} | {'-' if radius is None else f'{radius:.3g}'} | {layer} | "
                f"{fmt(share, 3)} | {pair('rad_ref_blur_rel')} | "
                f"{pair(f'rad_ref_{stage}_rel')} | {pair('rad_vis_blur_rel')} | "
                f"{pair(f'rad_vis_{stage}_rel')} | {verdict} |")
    add("")
    parts = []
    if met:
        parts.append("met on " + ", ".join(met))
    if missed:
        parts.append("missed on " + ", ".join(missed))
    add(f"Each cell is MAE / bias. Against the visible truth {after} the targets are "
        + " and ".join(parts) + " (scene (layers)).\n")
