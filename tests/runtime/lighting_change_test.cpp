// A changed key light under a still camera: the radiosity temporal filter
// must let the new lighting in at the motion blend's pace (history weight
// alpha for one frame), not at the running mean's n / (n + 1), which would
// keep the old lighting for hundreds of frames; an unchanged light set again
// must not disturb the running mean.
#include "sao_test_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

namespace deepgi::test {
namespace {

// Pixels (of those with visible E) where E equals w * history + (1 - w) * raw
// per channel within float rounding of half-float inputs.
struct Blend {
    std::size_t lit = 0, matching = 0;
};

Blend check_blend(const FloatImage& e, const FloatImage& history, const FloatImage& raw,
                  double history_weight) {
    Blend blend;
    for (std::size_t p = 0; p < e.pixels.size() / 3; ++p) {
        const double scale =
            std::max({history.pixels[3 * p], history.pixels[3 * p + 1], history.pixels[3 * p + 2],
                      raw.pixels[3 * p], raw.pixels[3 * p + 1], raw.pixels[3 * p + 2]});
        if (scale <= 1e-3) continue;
        ++blend.lit;
        bool ok = true;
        for (int k = 0; k < 3; ++k) {
            const double expected = history_weight * history.pixels[3 * p + k] +
                                    (1.0 - history_weight) * raw.pixels[3 * p + k];
            ok = ok && std::abs(e.pixels[3 * p + k] - expected) <= 1e-4 * scale;
        }
        blend.matching += ok;
    }
    return blend;
}

TEST_CASE(
    "radiosity: a changed light blends in at the motion weight for a frame, the same light set "
    "again keeps the running mean",
    "[radiosity]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    RenderSettings settings = small_settings(128, 72);
    settings.shadow_map_size = 512;
    settings.radiosity.rho_prop = 0.0f;
    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
    constexpr int still_frames = 20;
    for (int frame = 0; frame < still_frames; ++frame) renderer.render(scene.default_camera);

    // The same light again: frame 21 of the running mean, weight 20 / 21.
    FloatImage history = renderer.read_pass_output("radiosity-irradiance-layer0");
    renderer.set_key_light(renderer.key_light());
    renderer.render(scene.default_camera);
    Blend same = check_blend(renderer.read_pass_output("radiosity-irradiance-layer0"), history,
                             renderer.read_pass_output("radiosity-raw-layer0"),
                             double(still_frames) / double(still_frames + 1));
    INFO("unchanged light: " << same.matching << " of " << same.lit << " pixels are frame "
                             << still_frames + 1 << " of the running mean");
    REQUIRE(same.lit > 1000);
    CHECK(double(same.matching) >= 0.999 * double(same.lit));

    // A brighter light: the history weighs alpha, as under motion.
    history = renderer.read_pass_output("radiosity-irradiance-layer0");
    KeyLight brighter = renderer.key_light();
    brighter.intensity *= 2.0f;
    renderer.set_key_light(brighter);
    renderer.render(scene.default_camera);
    const FloatImage raw = renderer.read_pass_output("radiosity-raw-layer0");
    const FloatImage e = renderer.read_pass_output("radiosity-irradiance-layer0");
    Blend changed = check_blend(e, history, raw, settings.radiosity.alpha);
    INFO("changed light: " << changed.matching << " of " << changed.lit << " pixels blend at alpha "
                           << settings.radiosity.alpha);
    CHECK(double(changed.matching) >= 0.999 * double(changed.lit));
    // And the next frame is still again: its count restarts from the blend's
    // 1 / (1 - alpha) frames, so it is not the blend weight any more.
    history = e;
    renderer.render(scene.default_camera);
    Blend after =
        check_blend(renderer.read_pass_output("radiosity-irradiance-layer0"), history,
                    renderer.read_pass_output("radiosity-raw-layer0"), settings.radiosity.alpha);
    INFO("the frame after: " << after.matching << " of " << after.lit
                             << " pixels at the blend weight");
    CHECK(double(after.matching) < 0.5 * double(after.lit));
}

}  // namespace
}  // namespace deepgi::test
