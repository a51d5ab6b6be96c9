#!/usr/bin/python3
"""Where a still camera's E error sits after n frames
(docs/radiosity-studies.md, "Where cornell's error after 16 frames sits").

Reads the PFMs that `temporal_convergence --maps DIR` writes for one scene
(blurred E, layer 0's E before the blur, the converged images, depth and
normals) and prints the share of sum (E - C)^2 over the surface pixels held
by: the worst pixels, the viewport's border, creases and depth edges, each
surface orientation; the error left after box means of the signed error;
and the spatial autocorrelation of the error before and after the blur.

    scripts/e_error_where.py DIR [--scene cornell] [--frames 16]
"""
import argparse

import numpy as np

from report_plots.data import read_pfm


def grow(mask, r):
    out = np.zeros_like(mask)
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            out |= np.roll(np.roll(mask, dy, 0), dx, 1)
    return out


def box_mean(image, surface, r):
    """Mean of `image` (H x W) over the surface pixels of a (2r+1)^2 window."""
    kernel = np.ones(2 * r + 1)

    def smooth(a):
        a = np.apply_along_axis(lambda v: np.convolve(v, kernel, "same"), 0, a)
        return np.apply_along_axis(lambda v: np.convolve(v, kernel, "same"), 1, a)

    return smooth(image * surface) / np.maximum(smooth(surface.astype(float)), 1e-9) * surface


def autocorrelation(e, surface, lag):
    r = []
    for dy, dx in ((0, lag), (lag, 0)):
        h, w = e.shape
        a, b = e[: h - dy, : w - dx], e[dy:, dx:]
        m = surface[: h - dy, : w - dx] & surface[dy:, dx:]
        r.append(np.corrcoef(a[m], b[m])[0, 1])
    return np.mean(r)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("dir")
    parser.add_argument("--scene", default="cornell")
    parser.add_argument("--frames", type=int, default=16)
    args = parser.parse_args()
    load = lambda tag: read_pfm(f"{args.dir}/{args.scene}-{tag}.pfm", all_channels=True)
    depth = load("depth")[..., 0]
    normal = load("normal")
    surface = depth > 0
    C, E = load("e-converged"), load(f"e-{args.frames}")
    Cu, Eu = load("e-unblurred-converged")[..., :3], load(f"e-unblurred-{args.frames}")[..., :3]
    err = ((E - C) ** 2).sum(-1) * surface
    c2 = (C**2).sum(-1) * surface
    total = err.sum()
    print(f"{args.scene}, {args.frames} frames, {surface.sum()} surface pixels")
    print(f"  blurred E: relative RMS {100 * np.sqrt(total / c2.sum()):.2f}%")
    eu, cu2 = ((Eu - Cu) ** 2).sum(-1) * surface, (Cu**2).sum(-1) * surface
    print(f"  E before the blur: relative RMS {100 * np.sqrt(eu.sum() / cu2.sum()):.2f}%")

    ranked = np.sort(err[surface])[::-1].cumsum() / total
    print("  worst pixels' share of sum (E - C)^2: " + ", ".join(
        f"top {100 * q:g}% {100 * ranked[int(q * len(ranked)) - 1]:.1f}%"
        for q in (0.01, 0.05, 0.1, 0.25)))

    def share(mask, name):
        m = mask & surface
        print(f"  {name}: {100 * m.sum() / surface.sum():.1f}% of the pixels, "
              f"{100 * err[m].sum() / total:.1f}% of the error, relative RMS there "
              f"{100 * np.sqrt(err[m].sum() / max(c2[m].sum(), 1e-30)):.2f}%")

    h, w = depth.shape
    yy, xx = np.mgrid[0:h, 0:w]
    for b in (2, 4, 8):
        share((xx < b) | (yy < b) | (xx >= w - b) | (yy >= h - b), f"within {b} px of the border")
    crease = np.zeros_like(surface)
    edge = np.zeros_like(surface)
    for dy, dx in ((0, 1), (1, 0)):
        n2 = np.roll(np.roll(normal, -dy, 0), -dx, 1)
        d2 = np.roll(np.roll(depth, -dy, 0), -dx, 1)
        crease |= (normal * n2).sum(-1) < 0.9
        edge |= np.abs(d2 - depth) > 0.05 * np.maximum(depth, 1e-6)
    for r in (1, 2, 4):
        share(grow(crease & surface, r), f"within {r} px of a crease (normals' cos < 0.9)")
        share(grow(edge & surface, r), f"within {r} px of a depth edge (over 5%)")
    lum = C.mean(-1)
    share(lum >= np.quantile(lum[surface], 0.9), "the brightest 10% of the converged E")

    axis = np.argmax(np.abs(normal), -1)
    sign = np.sign(np.take_along_axis(normal, axis[..., None], -1)[..., 0])
    for a in range(3):
        for s in (-1, 1):
            m = surface & (axis == a) & (sign == s)
            if not m.any():
                continue
            before = np.sqrt(eu[m].sum() / cu2[m].sum())
            after = np.sqrt(err[m].sum() / c2[m].sum())
            share(m, f"view-space normal {'+' if s > 0 else '-'}{'xyz'[a]} (mean column "
                  f"{xx[m].mean():.0f} of {w}); before the blur {100 * before:.1f}%, "
                  f"blur's ratio {after / before:.2f}")

    signed = (E - C) * surface[..., None]
    for r in (2, 4, 10):
        low = np.stack([box_mean(signed[..., c], surface, r) for c in range(3)], -1)
        print(f"  left after a {2 * r + 1}x{2 * r + 1} box mean of E - C: "
              f"{100 * (low**2).sum() / total:.1f}% of sum (E - C)^2")
    for tag, a, c in (("before the blur", Eu, Cu), ("after the blur", E, C)):
        rel = ((a - c) / np.maximum(np.sqrt((c**2).sum(-1, keepdims=True)), 1e-3)).sum(-1)
        print(f"  autocorrelation of the relative error {tag}, lag 1, 2, 4, 8 px: " + ", ".join(
            f"{autocorrelation(rel * surface, surface, lag):+.2f}" for lag in (1, 2, 4, 8)))


if __name__ == "__main__":
    main()
