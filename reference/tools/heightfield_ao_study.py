#!/usr/bin/env python3
"""What a screen-space estimator could reach if it trusted the depth layers as
solid: ambient visibility by marching cosine-weighted rays through the dumped
G-buffer, against the ray-traced reference.

A study, not a renderer pass: it answers whether a horizon or ray-marching
estimator over the same two layers (XeGTAO's family), given a guess at how
thick each stored surface is, would meet the accuracy targets that deep SAO's
solid-angle estimator misses. Each stored surface is taken as a slab
`thickness` metres deep behind it along the view ray; a ray point is inside
the scene when it lies behind the plane of the layer-0 (or layer-1) surface at
the pixel it projects to, behind that pixel's stored depth, and less than the
thickness beyond it. The thickness is `--thickness` metres, or with
`--footprint K` K times the depth range the pixel's footprint spans on its
tangent plane, clamped to [--min-thickness, --thickness]: a surface seen
edge-on spans a long range of depth in one pixel, one seen head-on almost none.
The first such point within the radius, refined to where the segment crosses
that plane, gives the hit distance d, and AV = 1 - mean f(d), f = 1 - d^2 /
r^2, as the reference defines it. Rays are stratified (a jittered grid on the
cosine-weighted disk, rotated per pixel), many per pixel and unblurred, so the
figures show the estimator's bias rather than its noise.

usage: heightfield_ao_study.py DUMP_DIR REFERENCE_DIR --fov DEGREES
           [--guard PIXELS] [--radius M] [--thickness M] [--footprint K]
           [--min-thickness M] [--rays N] [--steps N] [--layers 1|2]
DUMP_DIR is `deepgi --headless --dump`, REFERENCE_DIR `deepgi reference`, of
the same scene and size; --fov is the scene camera's vertical field of view
(cornell 40, atrium and warehouse 60, the ref-* scenes 50).
"""
import argparse
import math
import sys

import numpy as np


def read_pfm(path):
    """All channels, rows bottom to top as stored (the pixel grid's order)."""
    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(height, width, 3 if kind == b"PF" else 1).astype(np.float64)


def camera_positions(depth, ray_scale):
    """Camera-space points of every pixel centre, as camera_position_at()."""
    height, width = depth.shape
    y, x = np.mgrid[0:height, 0:width]
    ndc_x = (x + 0.5) / width * 2.0 - 1.0
    ndc_y = (y + 0.5) / height * 2.0 - 1.0
    return np.stack([ndc_x * ray_scale[0] * depth, ndc_y * ray_scale[1] * depth, -depth], -1)


def tangent_frame(n):
    """Orthonormal tangents of unit normals (the reference's branchless frame)."""
    sign = np.where(n[:, 2] >= 0.0, 1.0, -1.0)
    a = -1.0 / (sign + n[:, 2])
    c = n[:, 0] * n[:, 1] * a
    t = np.stack([1.0 + sign * n[:, 0] ** 2 * a, sign * c, -sign * n[:, 0]], 1)
    b = np.stack([c, sign + n[:, 1] ** 2 * a, -n[:, 1]], 1)
    return t, b


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dump")
    parser.add_argument("reference")
    parser.add_argument("--fov", type=float, required=True)
    parser.add_argument("--guard", type=int, default=18)
    parser.add_argument("--radius", type=float, default=0.5)
    parser.add_argument("--thickness", type=float, default=0.1)
    parser.add_argument("--footprint", type=float, default=0.0)
    parser.add_argument("--min-thickness", type=float, default=0.0)
    parser.add_argument("--rays", type=int, default=64)
    parser.add_argument("--steps", type=int, default=48)
    parser.add_argument("--layers", type=int, choices=(1, 2), default=2)
    args = parser.parse_args()

    depth = [read_pfm(f"{args.dump}/gbuffer-depth-layer{k}.pfm")[..., 0] for k in (0, 1)]
    normal = [read_pfm(f"{args.dump}/gbuffer-normal-layer{k}.pfm") for k in (0, 1)]
    truth = read_pfm(f"{args.reference}/reference-ao-visibility.pfm")[..., 0]
    traced = read_pfm(f"{args.reference}/reference-depth-layer0.pfm")[..., 0]
    height, width = depth[0].shape
    if truth.shape != depth[0].shape:
        sys.exit(f"heightfield_ao_study: dump is {width}x{height}, reference "
                 f"{truth.shape[1]}x{truth.shape[0]}")
    g, r = args.guard, args.radius
    # The guard band widens the frustum and keeps the focal length.
    scale_y = math.tan(math.radians(args.fov) / 2.0) * height / (height - 2 * g)
    ray_scale = (scale_y * width / height, scale_y)
    position = [camera_positions(d, ray_scale) for d in depth]
    thickness = [np.full(d.shape, args.thickness) for d in depth]
    if args.footprint > 0:
        # Depth per pixel along x and y on the tangent plane, d z / d ndc =
        # z n_i scale_i / (n . ray), ray the view ray scaled to unit depth;
        # the clamp keeps a surface seen edge-on finite.
        for k in (0, 1):
            n = normal[k] / np.maximum(np.linalg.norm(normal[k], axis=-1, keepdims=True), 1e-12)
            ray = position[k] / np.maximum(depth[k], 1e-12)[..., None]
            facing = np.maximum(np.abs(np.einsum("ijk,ijk->ij", n, ray)), 0.02)
            span = depth[k] * (np.abs(n[..., 0]) * ray_scale[0] * 2.0 / width +
                               np.abs(n[..., 1]) * ray_scale[1] * 2.0 / height) / facing
            thickness[k] = np.clip(args.footprint * span, args.min_thickness, args.thickness)

    # The pixels deepgi_compare_reference compares: viewport, both see a surface.
    mask = (depth[0] > 0) & (traced > 0) & (np.abs(depth[0] - traced) <= 1e-3 * traced)
    mask[:g] = mask[height - g:] = False
    mask[:, :g] = mask[:, width - g:] = False
    pixels = np.nonzero(mask)
    x0 = position[0][pixels]
    n0 = normal[0][pixels]
    n0 /= np.linalg.norm(n0, axis=1, keepdims=True)
    t0, b0 = tangent_frame(n0)
    count = len(x0)
    rng = np.random.default_rng(1)
    rotation = rng.random(count)
    side = max(1, int(round(math.sqrt(args.rays))))
    occlusion = np.zeros(count)
    for i in range(side):
        for j in range(side):
            u1 = (i + rng.random(count)) / side
            u2 = ((j + rng.random(count)) / side + rotation) % 1.0
            s, phi = np.sqrt(u1), 2.0 * math.pi * u2
            w = (t0 * (s * np.cos(phi))[:, None] + b0 * (s * np.sin(phi))[:, None] +
                 n0 * np.sqrt(1.0 - u1)[:, None])
            hit = np.full(count, np.inf)
            jitter = rng.random(count)
            previous = np.zeros(count)
            for step in range(args.steps):
                t = r * (step + jitter) / args.steps
                q = x0 + w * t[:, None]
                z = -q[:, 2]
                live = np.isinf(hit) & (z > 1e-3)
                safe_z = np.maximum(z, 1e-6)
                px = np.floor((q[:, 0] / safe_z / ray_scale[0] * 0.5 + 0.5) * width).astype(np.int64)
                py = np.floor((q[:, 1] / safe_z / ray_scale[1] * 0.5 + 0.5) * height).astype(np.int64)
                live &= (px >= 0) & (px < width) & (py >= 0) & (py < height)
                px, py = np.clip(px, 0, width - 1), np.clip(py, 0, height - 1)
                found = np.zeros(count, bool)
                crossing = t.copy()
                for layer in range(args.layers):
                    d = depth[layer][py, px]
                    p = position[layer][py, px]
                    n = normal[layer][py, px]
                    below = np.einsum("ij,ij->i", q - p, n)
                    # Behind the plane alone is not enough: the plane of a
                    # surface seen edge-on runs along the view ray, and a point
                    # in front of its stored depth but on the wrong side of it
                    # would count as inside.
                    inside = (live & ~found & (d > 0) & (below < -1e-3 * z) & (z > d) &
                              (z < d + thickness[layer][py, px]))
                    if layer == 1:  # behind layer 0's slab too, or it is layer 0's hit
                        inside &= z > depth[0][py, px]
                    # Where the segment from the previous step crossed the plane.
                    above = np.einsum("ij,ij->i", x0 + w * previous[:, None] - p, n)
                    fraction = np.where(above > 0, above / np.maximum(above - below, 1e-12), 1.0)
                    crossing = np.where(inside, previous + (t - previous) * fraction, crossing)
                    found |= inside
                hit[found] = crossing[found]
                previous = t
            occlusion += np.where(np.isfinite(hit), np.maximum(0.0, 1.0 - hit ** 2 / r ** 2), 0.0)
    visibility = 1.0 - occlusion / (side * side)
    error = visibility - truth[pixels]
    open_surface = truth[pixels] >= 0.9999
    shape = (f"{args.footprint} footprints in [{args.min_thickness}, {args.thickness}] m"
             if args.footprint > 0 else f"{args.thickness} m")
    print(f"heightfield AV, thickness {shape}, {side * side} rays, {args.steps} steps, "
          f"{args.layers} layer(s): {count} pixels, MAE {np.abs(error).mean():.4f}, "
          f"bias {error.mean():+.4f}, open pixels below 0.99: "
          f"{int((open_surface & (visibility < 0.99)).sum())} of {int(open_surface.sum())}")


if __name__ == "__main__":
    main()
