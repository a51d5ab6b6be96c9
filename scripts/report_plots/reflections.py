"""The summary's mirror section, from reflections.csv: per scene with mirror
pixels, layer count and reflection step count, how often the march finds the
surface the traced reflection hits, the radiance error, and the pass's cost;
and which scenes of the run have no mirror rows."""
import os

from .data import read_csv


def reflection_section(directory, scenes, add):
    rows = read_csv(os.path.join(directory, "reflections.csv"))
    if rows is None:
        return
    add("## Mirror reflections\n")
    mirrored = list(dict.fromkeys(r["scene"] for r in rows))
    without = [s for s in scenes if s not in mirrored]
    if not rows:
        add("No scene of this run has mirror pixels, so there are no mirror rows "
            f"({', '.join(without) or 'no scenes'}).\n")
        return
    frames = sorted({r["frames"] for r in rows})
    add("The reflection pass against the ray-traced mirror reflections, over the viewport's "
        "mirror pixels where the rasterised and traced layer-0 depths agree "
        f"(docs/reflections.md): the filtered radiance after {', '.join(frames)} still frames "
        "of each configuration, the configurations taking turns frame by frame; the pass's "
        "milliseconds are their median. 'Same surface': the renderer's hit texel stores the "
        "surface the traced ray hits first (both missing counts); 'missed': the march found "
        "nothing where the traced ray hits; 'other': another surface; 'renderer only': a hit "
        "where the traced ray leaves the scene. Radiance errors are relative to the traced "
        "radiance's sum, over all compared pixels, over the same-surface ones, and over those "
        "whose traced ray meets another mirror first ('via a mirror': the march then marches "
        "once more from the mirror texel it hits). Every row is in `reflections.csv`.\n")
    add("| scene | layers | steps | mirror pixels | same surface | missed | other | renderer only "
        "| rel. MAE | bias | rel. MAE, same surface | bias, same surface | via a mirror "
        "| rel. MAE, via a mirror | bias, via a mirror | reflection (ms) |")
    add("|:--|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|")

    def cell(row, column, signed=False):
        text = row[column]
        if text == "":
            return "-"
        return f"{float(text):+.3f}" if signed else f"{float(text):.3f}"

    for r in rows:
        add(f"| {r['scene']} | {r['layers']} | {r['steps']} | {r['mirror_pixels']} | "
            f"{cell(r, 'same_surface')} | {cell(r, 'renderer_missed')} | "
            f"{cell(r, 'other_surface')} | {cell(r, 'renderer_only')} | {cell(r, 'rel_mae')} | "
            f"{cell(r, 'rel_bias', True)} | {cell(r, 'same_surface_rel_mae')} | "
            f"{cell(r, 'same_surface_rel_bias', True)} | {cell(r, 'meets_mirror')} | "
            f"{cell(r, 'meets_mirror_rel_mae')} | {cell(r, 'meets_mirror_rel_bias', True)} | "
            f"{float(r['reflection_ms']):.1f} |")
    add("")
    # What the second layer buys, per scene at each step count both layer
    # counts ran.
    for scene in mirrored:
        pairs = []
        for steps in dict.fromkeys(r["steps"] for r in rows if r["scene"] == scene):
            by_layers = {r["layers"]: r for r in rows
                         if r["scene"] == scene and r["steps"] == steps}
            if "1" in by_layers and "2" in by_layers:
                one, two = by_layers["1"], by_layers["2"]
                pairs.append(f"{steps} steps: same surface {float(one['same_surface']):.3f} -> "
                             f"{float(two['same_surface']):.3f}, missed "
                             f"{float(one['renderer_missed']):.3f} -> "
                             f"{float(two['renderer_missed']):.3f}")
        if pairs:
            add(f"- **{scene}, one layer -> two:** " + "; ".join(pairs) + ".")
    if without:
        add(f"- **No mirror rows:** {', '.join(without)} (no mirror material, or no mirror "
            "pixel in view).")
    add("")
