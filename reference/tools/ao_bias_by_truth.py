#!/usr/bin/env python3
"""Where an AO estimate's bias sits: its mean error against the ray-traced
truth, split by how occluded the truth says each pixel is.

The pixels are those deepgi_compare_reference measures (inside the guard band,
where the rasteriser and the ray tracer see the same surface); the estimate is
clamped to [0, 1] as compose uses it. Each bucket of truth AV gets its share of
the scene's bias (its summed error over all pixels, so the buckets add up to
the bias), its share of the pixels and its mean error, for the raw and the
blurred AO. A bias that a systematic cause (a falloff, a normalisation) makes
would spread over every occluded bucket; one that a kind of geometry makes
sits in a few.

usage: ao_bias_by_truth.py DUMP_DIR REFERENCE_DIR [GUARD]
DUMP_DIR is `deepgi --headless --dump`, REFERENCE_DIR `deepgi reference`, of
the same scene and size (reference/tools/measure_ao.sh writes both); GUARD is
the guard band in pixels (default: lround(0.1 * viewport height), as deepgi
takes it).
Standard library only, so that it runs wherever the renderer does.
"""
import sys

from pfm import read_pfm

BUCKETS = [(0.9999, 2.0, "open"), (0.97, 0.9999, ".97-1"), (0.9, 0.97, ".9-.97"),
           (0.7, 0.9, ".7-.9"), (-1.0, 0.7, "<.7")]


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    dump, reference = sys.argv[1], sys.argv[2]
    width, height, truth = read_pfm(reference + "/reference-ao-visibility.pfm")
    traced = read_pfm(reference + "/reference-depth-layer0.pfm")[2]
    depth = read_pfm(dump + "/gbuffer-depth-layer0.pfm")[2]
    estimates = {name: read_pfm(f"{dump}/ao-{name}.pfm")[2] for name in ("raw", "blurred")}
    # The buffer is the viewport plus the guard band on each side: the
    # viewport's height is the buffer's over 1.2.
    guard = int(sys.argv[3]) if len(sys.argv) == 4 else int(round(0.1 * round(height / 1.2)))
    pixels = [y * width + x for y in range(guard, height - guard) for x in range(guard, width - guard)
              if depth[y * width + x] > 0 and traced[y * width + x] > 0
              and abs(depth[y * width + x] - traced[y * width + x]) <= 1e-3 * traced[y * width + x]]
    count = len(pixels)
    for name, estimate in estimates.items():
        errors = {i: min(max(estimate[i], 0.0), 1.0) - truth[i] for i in pixels}
        print(f"ao-{name}: {count} pixels, bias {sum(errors.values()) / count:+.4f}")
        for low, high, label in BUCKETS:
            inside = [i for i in pixels if low <= truth[i] < high]
            if not inside:
                continue
            total = sum(errors[i] for i in inside)
            print(f"  truth {label:7} {len(inside) / count:6.1%} of pixels: "
                  f"{total / count:+.4f} of the bias, mean error {total / len(inside):+.4f}")


if __name__ == "__main__":
    main()
