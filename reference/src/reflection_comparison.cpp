#include "deepgi/reflection_comparison.hpp"

#include "deepgi/same_surface_depth.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace deepgi {

namespace {

void add(RadianceSums& sums, double rendered, double traced) {
    sums.truth += traced;
    sums.absolute_error += std::abs(rendered - traced);
    sums.error += rendered - traced;
}

void check_sizes(const ReflectionComparisonImages& images) {
    const FloatImage& truth = images.truth;
    for (const FloatImage* image :
         {&images.raster_depth, &images.hit, &images.radiance, &images.filtered,
          &images.traced_depth, &images.truth_hit, &images.surfaces})
        if (image->width != truth.width || image->height != truth.height)
            throw std::invalid_argument(fmt::format("reflection images of {}x{} and {}x{}",
                                                    image->width, image->height, truth.width,
                                                    truth.height));
    if (truth.channels != 3 || images.hit.channels < 3 || images.radiance.channels < 3 ||
        images.filtered.channels < 3 || images.surfaces.channels != 3 ||
        images.truth_hit.channels != 3)
        throw std::invalid_argument("reflection images without their channels");
    if (images.meets_mirror &&
        images.meets_mirror->size() != std::size_t(truth.width) * std::size_t(truth.height))
        throw std::invalid_argument("a meets-mirror mask of another size than the images");
}

}  // namespace

ReflectionComparison compare_reflection_images(const ReflectionComparisonImages& images,
                                               int guard) {
    check_sizes(images);
    const FloatImage& truth = images.truth;
    const FloatImage& hit = images.hit;
    ReflectionComparison result;
    for (int y = guard; y < truth.height - guard; ++y)
        for (int x = guard; x < truth.width - guard; ++x) {
            if (!same_surface_depth(images.raster_depth.at(x, y), images.traced_depth.at(x, y)))
                continue;
            if (images.surfaces.at(x, y, 2) != 1.0f || hit.at(x, y, 2) <= -2.0f) continue;
            ++result.mirror_pixels;
            // The renderer's hit texel, mapped to the surface the reference's
            // camera ray finds in that layer there.
            const int layer = int(hit.at(x, y, 2));
            int surface = -1;
            if (layer >= 0) {
                const int hx = std::clamp(int(std::floor(hit.at(x, y, 0))), 0, hit.width - 1);
                const int hy = std::clamp(int(std::floor(hit.at(x, y, 1))), 0, hit.height - 1);
                surface = int(images.surfaces.at(hx, hy, std::min(layer, 1)));
            }
            const int expected = int(images.truth_hit.at(x, y, 0));
            const bool agree = surface == expected;
            if (agree) {
                ++result.same_surface;
                if (expected < 0) ++result.both_miss;
            } else if (surface < 0) {
                ++result.renderer_missed;
            } else if (expected < 0) {
                ++result.renderer_only;
            } else {
                ++result.wrong_surface;
            }
            const bool chain =
                images.meets_mirror &&
                (*images.meets_mirror)[std::size_t(y) * std::size_t(truth.width) + std::size_t(x)];
            result.meets_mirror += chain;
            for (int c = 0; c < 3; ++c) {
                const double t = truth.at(x, y, c), filtered = images.filtered.at(x, y, c);
                add(result.radiance, images.radiance.at(x, y, c), t);
                add(result.filtered, filtered, t);
                if (agree) add(result.same_surface_filtered, filtered, t);
                if (chain) add(result.meets_mirror_filtered, filtered, t);
            }
        }
    return result;
}

}  // namespace deepgi
