#pragma once
// The report's comparisons of an estimate with its truth, inside the report
// library: masks of the pixels compared, means, relative errors and the
// open-surface counts (the public compare_images is in deepgi/report.hpp).
#include "deepgi/image_io.hpp"
#include "deepgi/reference.hpp"
#include "deepgi/report.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace deepgi::report {

// The blurred AV as compose uses it: the solid-angle estimate is signed up
// to there (sao.frag) and compose clamps it to [0, 1], as
// deepgi_compare_reference does. Raw and temporal AV stay signed: they are
// the estimator's stages, whose bias the report measures.
FloatImage clamped_visibility(FloatImage image);

// Pixels inside the viewport (the guard band excluded) where `keep` holds.
template <class Keep>
std::vector<std::uint8_t> viewport_mask(int width, int height, int guard, Keep keep) {
    std::vector<std::uint8_t> mask(std::size_t(width) * std::size_t(height), 0);
    for (int y = guard; y < height - guard; ++y) {
        for (int x = guard; x < width - guard; ++x) {
            mask[std::size_t(y) * std::size_t(width) + std::size_t(x)] = keep(x, y) ? 1 : 0;
        }
    }
    return mask;
}

// The ray-traced one-bounce irradiance that the radiosity gather estimates
// (viewport layout as ambient_visibility); empty when it was not traced.
std::optional<FloatImage> reference_irradiance(const ReferenceImages& images);

// The visible truth of `layers` G-buffer layers: the part of that irradiance
// whose source surface layer 0 holds, plus layer 1's with two layers
// (ReferenceImages), the most a gather over those layers can find
// (docs/radiosity.md, "Against the light the layers hold").
std::optional<FloatImage> visible_irradiance(const ReferenceImages& images, int layers);

// The mean of `image` over the mask.
double masked_mean(const FloatImage& image, const std::vector<std::uint8_t>& mask);

// Relative to the mean of the converged image: irradiance has no natural
// unit, and the scenes differ in brightness by orders of magnitude.
ErrorStats relative(ErrorStats stats, double scale);

// The viewport of `image`'s first channel, NaN outside the mask.
FloatImage crop(const FloatImage& image, int guard, const std::vector<std::uint8_t>& mask);

// The open pixels whose neighbours within `reach` pixels (a square) are open
// too; reach 0: every open pixel. The target counts reach 1 before the blur,
// where the truth's own Monte Carlo estimate reads 1 next to occluded pixels
// when an occluder's reach ends inside the pixel, and the blur's radius after
// it, which rightly averages neighbours' occlusion in, as a blur of the truth
// would (docs/deep-sao.md, "Current figures").
std::vector<std::uint8_t> open_region(const FloatImage& truth, int reach);

// Pixels of mask and region, and of those, the ones whose estimate is below 0.99.
struct OpenCount {
    long long pixels = 0;
    long long below = 0;
};
OpenCount count_open(const FloatImage& estimate, const std::vector<std::uint8_t>& mask,
                     const std::vector<std::uint8_t>& region);

}  // namespace deepgi::report
