#!/usr/bin/env python3
"""Where an AO estimate's error sits on cornell: its mean absolute error
against the ray-traced truth, split by the kind of place each pixel is in.

Cornell's error is of both signs (docs/deep-sao-studies.md, "Cornell's
error by region"), so a bias hides it; this splits the MAE by region and, within each,
into its too-bright and too-dark parts. Each pixel's world position is
rebuilt from its depth with cornell's default camera (at (0, 1, 3.6), looking
down -z, 40 degrees vertical field of view, 16:9), and the room's and the
blocks' geometry (runtime/src/scene/scene_builtin.cpp) says where it is:

  back wall, within r of its edges      back-edge
  back wall, further in                 back-middle
  a block's face                        block-face
  floor or wall within r of a block     by-block
  floor, ceiling or side wall within r of another of them (the creases
  that run towards the camera), away from the back wall
                                        crease-floor-ceiling, crease-side
  the same within r of the back wall    crease-corner
  floor, ceiling or side wall within r of the back wall only
                                        by-back-wall
  the rest                              open-floor-ceiling, open-side

r is the AO radius the accuracy measurements use (0.5). The pixels are those
deepgi_compare_reference measures (inside the guard band, where the
rasteriser and the ray tracer see the same surface); each estimate is
clamped to [0, 1] as compose uses it. Every region's column is its share of
the scene's figure, so the rows add up to the last.

usage: ao_cornell_regions.py REFERENCE_DIR DUMP_DIR [DUMP_DIR...]
The directories are those reference/tools/measure_ao.sh writes for cornell
(`deepgi reference` and `deepgi --headless --dump`, same size, default
camera); each DUMP_DIR's ao-blurred.pfm is measured, the first one's
G-buffer gives the positions.
Standard library only, so that it runs wherever the renderer does.
"""
import math
import sys

from pfm import read_pfm

RADIUS = 0.5
FOV_DEGREES = 40.0
CAMERA_Z = 3.6
CAMERA_Y = 1.0
# Blocks: centre, half extents, turn about y (scene_builtin.cpp, make_cornell).
BLOCKS = [((-0.33, 0.6, -0.35), (0.28, 0.6, 0.28), 17.0), ((0.35, 0.3, 0.3), (0.28, 0.3, 0.28), -17.0)]


def block_distance(p):
    """Distance from p to the nearer block (0 inside); the turn's sign is
    taken both ways, so the convention of the builder does not matter."""
    best = math.inf
    for centre, half, degrees in BLOCKS:
        for angle in (math.radians(degrees), -math.radians(degrees)):
            dx, dz = p[0] - centre[0], p[2] - centre[2]
            local_x = math.cos(angle) * dx - math.sin(angle) * dz
            local_z = math.sin(angle) * dx + math.cos(angle) * dz
            outside = [max(abs(local_x) - half[0], 0.0), max(abs(p[1] - centre[1]) - half[1], 0.0),
                       max(abs(local_z) - half[2], 0.0)]
            best = min(best, math.sqrt(sum(v * v for v in outside)))
    return best


def region(p):
    walls = {"back": p[2] + 1.0, "left": p[0] + 1.0, "right": 1.0 - p[0], "floor": p[1], "ceiling": 2.0 - p[1]}
    on = [name for name, distance in walls.items() if distance < 0.01]
    if not on:
        return "block-face"
    surface = on[0]
    if block_distance(p) < RADIUS:
        return "by-block"
    if surface == "back":
        edge = min(walls["left"], walls["right"], walls["floor"], walls["ceiling"])
        return "back-edge" if edge < RADIUS else "back-middle"
    side = surface in ("left", "right")
    other = min(walls["floor"], walls["ceiling"]) if side else min(walls["left"], walls["right"])
    near_back = walls["back"] < RADIUS
    if other < RADIUS:
        return "crease-corner" if near_back else ("crease-side" if side else "crease-floor-ceiling")
    if near_back:
        return "by-back-wall"
    return "open-side" if side else "open-floor-ceiling"


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    reference, dumps = sys.argv[1], sys.argv[2:]
    width, height, truth = read_pfm(reference + "/reference-ao-visibility.pfm")
    traced = read_pfm(reference + "/reference-depth-layer0.pfm")[2]
    depth = read_pfm(dumps[0] + "/gbuffer-depth-layer0.pfm")[2]
    # The buffer is the viewport plus the guard band on each side: the
    # viewport's height is the buffer's over 1.2.
    view_height = int(round(height / 1.2))
    guard = int(round(0.1 * view_height))
    view_width = width - 2 * guard
    tangent = math.tan(math.radians(FOV_DEGREES / 2))
    pixels = []
    for y in range(guard, height - guard):
        for x in range(guard, width - guard):
            i = y * width + x
            if not (depth[i] > 0 and traced[i] > 0 and abs(depth[i] - traced[i]) <= 1e-3 * traced[i]):
                continue
            z = depth[i]
            ndc_x = (x - guard + 0.5) / (view_width / 2) - 1.0
            ndc_y = (y - guard + 0.5) / (view_height / 2) - 1.0
            p = (ndc_x * tangent * view_width / view_height * z, ndc_y * tangent * z + CAMERA_Y, CAMERA_Z - z)
            pixels.append((i, region(p)))
    count = len(pixels)
    estimates = [(d, read_pfm(d + "/ao-blurred.pfm")[2]) for d in dumps]
    print(f"{count} pixels; per estimate: MAE, bias, and the MAE's too-bright and too-dark parts")
    labels = ["/".join(d.rstrip("/").split("/")[-2:])[-31:] for d in dumps]
    print(f"{'region':22} {'pixels':>7}" + "".join(f" | {label:>31}" for label in labels))
    names = sorted({name for _, name in pixels})
    for name in names + ["all"]:
        inside = [i for i, n in pixels if name in ("all", n)]
        line = f"{name:22} {len(inside) / count:7.1%}"
        for _, estimate in estimates:
            errors = [min(max(estimate[i], 0.0), 1.0) - truth[i] for i in inside]
            bright = sum(e for e in errors if e > 0) / count
            dark = -sum(e for e in errors if e < 0) / count
            line += f" | {bright + dark:.4f} {bright - dark:+.4f} {bright:.4f} {dark:.4f}"
        print(line)


if __name__ == "__main__":
    main()
