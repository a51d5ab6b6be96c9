// The reflection comparison (deepgi/reflection_comparison.hpp) on images
// made by hand, 7x4 with a guard band of one pixel: each interior pixel is
// set up to fall in one class (or to be left out for one reason), and every
// count and sum is worked out by hand below. The guard band's pixels would
// all count as missed mirrors with a traced radiance of 100, so any of them
// counted shows.
#include "deepgi/reflection_comparison.hpp"
#include "deepgi/same_surface_depth.hpp"

#include <catch2/catch.hpp>

#include <stdexcept>
#include <vector>

namespace {

deepgi::FloatImage image(int channels, float value) {
    deepgi::FloatImage result;
    result.width = 7;
    result.height = 4;
    result.channels = channels;
    result.pixels.assign(std::size_t(7 * 4 * channels), value);
    return result;
}

void set(deepgi::FloatImage& target, int x, int y, std::vector<float> values) {
    for (int c = 0; c < target.channels; ++c)
        target.pixels[(std::size_t(y) * std::size_t(target.width) + std::size_t(x)) *
                          std::size_t(target.channels) +
                      std::size_t(c)] = values.size() == 1 ? values[0] : values[std::size_t(c)];
}

// The hand-made frame. The hit texels (0, 0) and (1, 0), in the guard band,
// store surfaces 10 and 20 in layer 0 and 11 and 21 in layer 1.
struct HandMadeFrame {
    deepgi::FloatImage raster = image(1, 2.0f), traced = image(1, 2.0f);
    deepgi::FloatImage hit = image(3, -1.0f);        // every ray missed...
    deepgi::FloatImage truth_hit = image(3, 30.0f);  // ...where the truth hits 30
    deepgi::FloatImage surfaces = image(3, 1.0f);    // every pixel a mirror
    deepgi::FloatImage truth = image(3, 100.0f), radiance = image(3, 0.0f),
                       filtered = image(3, 0.0f);
    std::vector<std::uint8_t> meets_mirror = std::vector<std::uint8_t>(7 * 4, 1);

    // A compared pixel: the renderer's hit, the traced surface, and the
    // traced, this frame's and the filtered radiance (the same in the
    // three channels).
    void pixel(int x, int y, std::vector<float> renderer_hit, float traced_surface, float t,
               float r, float f, bool chain = false) {
        set(hit, x, y, renderer_hit);
        set(truth_hit, x, y, {traced_surface, -1.0f, 0.0f});
        set(truth, x, y, {t});
        set(radiance, x, y, {r});
        set(filtered, x, y, {f});
        meets_mirror[std::size_t(y * 7 + x)] = chain;
    }

    HandMadeFrame() {
        set(surfaces, 0, 0, {10.0f, 11.0f, 1.0f});
        set(surfaces, 1, 0, {20.0f, 21.0f, 1.0f});
        // Same surface: texel (0, 0), layer 0 stores 10, the truth hits 10.
        pixel(1, 1, {0.5f, 0.5f, 0.0f}, 10.0f, 1.0f, 1.5f, 1.25f);
        // Same surface, both miss.
        pixel(2, 1, {0.0f, 0.0f, -1.0f}, -1.0f, 0.5f, 0.5f, 0.5f);
        // Renderer missed: the march found nothing, the truth hits 20.
        pixel(3, 1, {0.0f, 0.0f, -1.0f}, 20.0f, 2.0f, 0.0f, 0.5f);
        // Wrong surface: texel (1, 0) of layer 1 stores 21, the truth hits 20;
        // the traced ray meets a mirror there.
        pixel(4, 1, {1.7f, 0.2f, 1.0f}, 20.0f, 1.0f, 3.0f, 2.0f, true);
        // Renderer only: the march hit 10 where the traced ray leaves.
        pixel(5, 1, {0.5f, 0.5f, 0.0f}, -1.0f, 0.0f, 1.0f, 0.5f);
        // Same surface in layer 1: texel (0, 0) stores 11 there.
        pixel(1, 2, {0.9f, 0.9f, 1.0f}, 11.0f, 0.5f, 0.25f, 0.75f);
        // Left out: not a mirror for the reference...
        pixel(2, 2, {0.5f, 0.5f, 0.0f}, 10.0f, 100.0f, 0.0f, 0.0f, true);
        set(surfaces, 2, 2, {10.0f, 11.0f, 0.0f});
        // ...nor for the renderer (layer -2)...
        pixel(3, 2, {0.5f, 0.5f, -2.0f}, 10.0f, 100.0f, 0.0f, 0.0f, true);
        // ...depths 2 and 2.01 apart by 5e-3 relative, over 1e-3...
        pixel(4, 2, {0.5f, 0.5f, 0.0f}, 10.0f, 100.0f, 0.0f, 0.0f, true);
        set(traced, 4, 2, {2.01f});
        // ...and no rasterised surface.
        pixel(5, 2, {0.5f, 0.5f, 0.0f}, 10.0f, 100.0f, 0.0f, 0.0f, true);
        set(raster, 5, 2, {0.0f});
    }

    deepgi::ReflectionComparisonImages images(bool with_mask = true) const {
        return {raster,    hit,      radiance,
                filtered,  traced,   truth,
                truth_hit, surfaces, with_mask ? &meets_mirror : nullptr};
    }
};

// Sums over three equal channels: three times the one channel's.
void check_sums(const char* what, const deepgi::RadianceSums& sums, double truth,
                double absolute_error, double error) {
    INFO(what);
    CHECK(sums.truth == 3 * truth);
    CHECK(sums.absolute_error == 3 * absolute_error);
    CHECK(sums.error == 3 * error);
}

}  // namespace

TEST_CASE("reference: the reflection comparison counts hand-made pixels as worked out by hand",
          "[reference]") {
    const HandMadeFrame frame;
    const deepgi::ReflectionComparison r = deepgi::compare_reflection_images(frame.images(), 1);
    // Six of the ten interior pixels are mirror pixels; three agree (one of
    // them both missing), one each missed, wrong and renderer only.
    CHECK(r.mirror_pixels == 6);
    CHECK(r.same_surface == 3);
    CHECK(r.both_miss == 1);
    CHECK(r.renderer_missed == 1);
    CHECK(r.wrong_surface == 1);
    CHECK(r.renderer_only == 1);
    CHECK(r.meets_mirror == 1);
    // Sums over the three channels of the six: truth 1 + 0.5 + 2 + 1 + 0 +
    // 0.5; this frame's |error| 0.5 + 0 + 2 + 2 + 1 + 0.25, error 0.5 + 0 - 2
    // + 2 + 1 - 0.25; filtered |error| 0.25 + 0 + 1.5 + 1 + 0.5 + 0.25, error
    // 0.25 + 0 - 1.5 + 1 + 0.5 + 0.25. Every value is exact in binary.
    check_sums("this frame's", r.radiance, 5.0, 5.75, 1.25);
    check_sums("filtered", r.filtered, 5.0, 3.5, 0.5);
    // The same-surface pixels (1, 1), (2, 1), (1, 2): truth 1 + 0.5 + 0.5,
    // filtered errors 0.25, 0, 0.25.
    check_sums("same surface", r.same_surface_filtered, 2.0, 0.5, 0.5);
    // The one pixel meeting a mirror, (4, 1): truth 1, filtered 2.
    check_sums("meets a mirror", r.meets_mirror_filtered, 1.0, 1.0, 1.0);

    // Without a mask no pixel meets a mirror, and the rest is unchanged.
    const deepgi::ReflectionComparison unmasked =
        deepgi::compare_reflection_images(frame.images(false), 1);
    CHECK(unmasked.meets_mirror == 0);
    CHECK(unmasked.meets_mirror_filtered.truth == 0.0);
    CHECK(unmasked.same_surface == 3);
    CHECK(unmasked.filtered.error == r.filtered.error);

    // With no guard band the 18 border pixels count too, each a missed
    // mirror (traced radiance 100, none rendered) meeting a mirror.
    const deepgi::ReflectionComparison whole = deepgi::compare_reflection_images(frame.images(), 0);
    CHECK(whole.mirror_pixels == 6 + 18);
    CHECK(whole.renderer_missed == 1 + 18);
    CHECK(whole.meets_mirror == 1 + 18);
    CHECK(whole.radiance.truth == 3 * (5.0 + 18 * 100.0));
}

TEST_CASE("reference: the same-surface depth test and the comparison's refusals", "[reference]") {
    // Within 1e-3 of the traced depth, and both on a surface.
    CHECK(deepgi::same_surface_depth(1.0f, 1.0005f));
    CHECK(deepgi::same_surface_depth(2.0f, 2.0f));
    CHECK_FALSE(deepgi::same_surface_depth(1.0f, 1.002f));
    CHECK_FALSE(deepgi::same_surface_depth(1.002f, 1.0f));
    CHECK_FALSE(deepgi::same_surface_depth(0.0f, 0.0f));
    CHECK_FALSE(deepgi::same_surface_depth(0.0f, 1.0f));
    CHECK_FALSE(deepgi::same_surface_depth(1.0f, 0.0f));

    HandMadeFrame frame;
    frame.traced.width = 6;  // pixels no longer match: any size mismatch is refused
    CHECK_THROWS_AS(deepgi::compare_reflection_images(frame.images(), 1), std::invalid_argument);
    HandMadeFrame one_channel;
    one_channel.truth = image(1, 1.0f);
    CHECK_THROWS_AS(deepgi::compare_reflection_images(one_channel.images(), 1),
                    std::invalid_argument);
    HandMadeFrame short_mask;
    short_mask.meets_mirror.pop_back();
    CHECK_THROWS_AS(deepgi::compare_reflection_images(short_mask.images(), 1),
                    std::invalid_argument);
}
