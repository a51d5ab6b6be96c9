#pragma once
// The renderer's mirror reflections against the traced ones
// (docs/reflections.md, "Against the ray tracer"): which surface each mirror
// pixel's march found against the one the traced ray hits, and the reflected
// radiance's error. deepgi_compare_reflections prints it for a dump and the
// report's mirror rows (docs/report.md) tabulate it; both take it from here,
// so that they count the same pixels the same way.
#include "deepgi/image_io.hpp"

#include <cstdint>
#include <vector>

namespace deepgi {

// The renderer's outputs and the reference's images of one frame, all of
// the same guard-banded size.
struct ReflectionComparisonImages {
    const FloatImage& raster_depth;  // gbuffer-depth-layer0
    const FloatImage& hit;           // reflection-hit: texel x, y, layer (-1 none, <= -2 no mirror)
    const FloatImage& radiance;      // reflection-radiance, this frame's
    const FloatImage& filtered;      // reflection-temporal (or the radiance again)
    const FloatImage& traced_depth;  // reference-depth-layer0
    const FloatImage& truth;         // reference-reflection-radiance
    const FloatImage& truth_hit;     // reference-reflection-hit: surface id, triangle (-1 none)
    const FloatImage& surfaces;      // reference-surface-layers: layer 0 and 1 ids, mirror flag
    // Per pixel, nonzero where the traced ray's first surface is itself a
    // mirror; may be null (then no pixel meets one).
    const std::vector<std::uint8_t>* meets_mirror = nullptr;
};

// Sums over a set of pixels and their three channels: of the traced
// radiance L_ref, of |L - L_ref| and of L - L_ref. Their ratios to `truth`
// are the relative mean absolute error and bias.
struct RadianceSums {
    double truth = 0.0;
    double absolute_error = 0.0;
    double error = 0.0;
};

// Counted over the viewport's pixels (guard band left out) where both call
// the pixel a mirror and the traced and rasterised layer-0 depths agree
// (same_surface_depth): the mirror pixels. Each is one of four: same
// surface (the surface the renderer's hit texel stores in the layer hit,
// as the reference's camera ray through that texel names it, is the one the
// traced ray hits first; both hitting nothing counts, and is counted again
// in both_miss), renderer missed (the march found nothing where the traced
// ray hits), wrong surface (both hit, different surfaces) and renderer only
// (the march hit where the traced ray leaves the scene).
struct ReflectionComparison {
    long long mirror_pixels = 0;
    long long same_surface = 0;
    long long both_miss = 0;
    long long renderer_missed = 0;
    long long wrong_surface = 0;
    long long renderer_only = 0;
    long long meets_mirror = 0;  // mirror pixels the meets_mirror mask marks
    RadianceSums radiance;       // this frame's radiance, every mirror pixel
    RadianceSums filtered;       // the filtered radiance, every mirror pixel
    // The filtered radiance over the same-surface pixels: the shading's own
    // error without the march's misses; and over the pixels meeting a mirror.
    RadianceSums same_surface_filtered;
    RadianceSums meets_mirror_filtered;
};

// Throws std::invalid_argument when the images differ in size or lack their
// channels (three for truth, truth_hit and surfaces, at least three for the
// renderer's hit and radiances).
ReflectionComparison compare_reflection_images(const ReflectionComparisonImages& images, int guard);

}  // namespace deepgi
