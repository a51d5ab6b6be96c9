// How deep SAO's visibility reaches the image: compose's terms times the
// blurred visibility, its sign through the temporal filter and the blur, the
// AO debug views, and an image that does not depend on the estimator with AO
// off. The estimator itself against its CPU evaluation is sao_test.cpp.
#include "sao_test_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace deepgi::test {
namespace {

float srgb_encode(float linear) {
    const float c = std::clamp(linear, 0.0f, 1.0f);
    return c < 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

TEST_CASE("sao: compose adds albedo times E and the environment, times the blurred visibility",
          "[compose]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    // Every combination of the three terms compose can leave out (docs/gallery.md's
    // direct-only / + AO / + bounces images): a term switched off must be
    // absent from the result, one switched on present.
    for (int terms = 0; terms < 8; ++terms) {
        const bool use_ao = (terms & 1) == 0;
        const bool use_radiosity = (terms & 2) == 0;
        const bool use_environment = (terms & 4) == 0;
        RenderSettings settings = small_settings(160, 90);
        // Solid angle: its AV is signed, so the clamp in compose is checked too.
        settings.ao.method = AoMethod::solid_angle;
        settings.ao.enabled = use_ao;
        settings.radiosity.enabled = use_radiosity;
        settings.environment = use_environment;
        Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
        renderer.render(scene.default_camera);
        const FloatImage composed = renderer.read_pass_output("compose-radiance");
        const FloatImage direct = renderer.read_pass_output("direct_light-radiance-layer0");
        const FloatImage emissive = renderer.read_pass_output("gbuffer-emissive-layer0");
        const FloatImage albedo = renderer.read_pass_output("gbuffer-albedo-layer0");
        const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
        const FloatImage visibility = renderer.read_pass_output("ao-blurred");
        const FloatImage irradiance = renderer.read_pass_output("radiosity-blurred");
        const FloatImage confidence = renderer.read_pass_output("radiosity-blurred-confidence");
        const float pi = 3.14159265f;
        int mismatches = 0;
        int visibility_matters = 0;
        int clamp_matters = 0;
        int radiosity_matters = 0;
        int environment_matters = 0;
        for (int y = 0; y < composed.height; ++y) {
            for (int x = 0; x < composed.width; ++x) {
                if (depth.at(x, y) <= 0.0f) continue;
                const float c = use_radiosity ? std::clamp(confidence.at(x, y), 0.0f, 1.0f) : 0.0f;
                // The solid-angle AV is signed until compose clamps it.
                const float av = use_ao ? std::clamp(visibility.at(x, y), 0.0f, 1.0f) : 1.0f;
                for (int k = 0; k < 3; ++k) {
                    // cornell has a black background: the environment is the
                    // constant ambient radiance, irradiance pi * ambient.
                    const float gathered = use_radiosity ? irradiance.at(x, y, k) : 0.0f;
                    const float environment =
                        use_environment ? pi * scene.ambient[k] * (1.0f - c) : 0.0f;
                    const float indirect = albedo.at(x, y, k) / pi * (gathered + environment);
                    const float expected =
                        direct.at(x, y, k) + emissive.at(x, y, k) + indirect * av;
                    // R11G11B10F keeps 6 or 5 mantissa bits: about 3% relative.
                    mismatches +=
                        std::abs(composed.at(x, y, k) - expected) > 0.035f * expected + 1e-5f;
                    visibility_matters += indirect * (1.0f - visibility.at(x, y)) > 0.1f * expected;
                    // Where the clamp changes the result by more than the
                    // tolerance: a compose without it fails here.
                    clamp_matters +=
                        use_ao && indirect * -visibility.at(x, y) > 0.035f * expected + 1e-5f;
                    radiosity_matters +=
                        albedo.at(x, y, k) / pi * irradiance.at(x, y, k) > 0.1f * expected;
                    environment_matters +=
                        albedo.at(x, y, k) * scene.ambient[k] * av > 0.1f * expected;
                }
            }
        }
        INFO("AO " << use_ao << ", radiosity " << use_radiosity << ", environment "
                   << use_environment);
        CHECK(mismatches == 0);
        // Pixels where the check fails if compose got the term's switch
        // wrong (the passes run either way, so the unused terms are there).
        if (use_radiosity || use_environment) CHECK(visibility_matters > 100);
        if (use_ao && (use_radiosity || use_environment)) CHECK(clamp_matters > 0);
        CHECK(radiosity_matters > 100);
        if (!use_radiosity) CHECK(environment_matters > 100);
    }
}

TEST_CASE("sao: the solid-angle visibility stays signed through the temporal filter and the blur",
          "[compose]") {
    // Clamping it per pixel before they average it biases the result bright
    // (sao.frag); a UNORM target or a clamp in either pass would show here.
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    RenderSettings settings = small_settings(160, 90);
    settings.ao.method = AoMethod::solid_angle;
    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
    renderer.render(scene.default_camera);
    const FloatImage raw = renderer.read_pass_output("ao-raw");
    const FloatImage temporal = renderer.read_pass_output("ao-temporal");
    const FloatImage blurred = renderer.read_pass_output("ao-blurred");
    int raw_negative = 0, temporal_mismatches = 0, blurred_negative = 0;
    for (std::size_t i = 0; i < raw.pixels.size(); ++i) {
        raw_negative += raw.pixels[i] < 0.0f;
        // The first frame has no history: the filter passes the raw value.
        temporal_mismatches += temporal.pixels[i] != raw.pixels[i];
        blurred_negative += blurred.pixels[i] < 0.0f;
    }
    INFO(raw_negative << " raw and " << blurred_negative << " blurred pixels below 0");
    CHECK(raw_negative > 10);
    CHECK(temporal_mismatches == 0);
    CHECK(blurred_negative > 0);
}

TEST_CASE("sao: the ao-raw, ao-temporal and ao-blurred debug views show the visibility",
          "[compose]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    for (auto [view, source] :
         {std::pair{DebugView::ao_raw, "ao-raw"}, std::pair{DebugView::ao_temporal, "ao-temporal"},
          std::pair{DebugView::ao_blurred, "ao-blurred"}}) {
        RenderSettings settings = small_settings(160, 90);
        settings.view = view;
        Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
        renderer.render(scene.default_camera);
        const std::vector<std::uint8_t> shown = renderer.read_output_rgba8();
        const FloatImage visibility = renderer.read_pass_output(source);
        const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
        const int guard = renderer.layout().guard;
        int mismatches = 0;
        int grey_levels = 0;
        for (int y = 0; y < settings.height; ++y) {
            for (int x = 0; x < settings.width; ++x) {
                const bool surface = depth.at(x + guard, y + guard) > 0.0f;
                const float expected =
                    surface ? srgb_encode(visibility.at(x + guard, y + guard)) : 0.0f;
                const float actual =
                    float(shown[(std::size_t(y) * std::size_t(settings.width) + std::size_t(x)) *
                                4]) /
                    255.0f;
                mismatches += std::abs(actual - expected) > 1.0f / 255.0f;
                grey_levels += surface && expected < 0.9f;
            }
        }
        INFO(source);
        CHECK(mismatches == 0);
        CHECK(grey_levels > 100);
    }
}

// With AO switched off the estimator must not matter: the SAO pass still
// runs (the debug views show it), and the march's back-face pass with it.
TEST_CASE("sao: with AO off the final image does not depend on the estimator", "[compose]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    std::vector<FloatImage> composed;
    for (AoMethod method : {AoMethod::solid_angle, AoMethod::march}) {
        RenderSettings settings = small_settings(160, 90);
        settings.ao.enabled = false;
        settings.ao.method = method;
        Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
        renderer.render(scene.default_camera);
        composed.push_back(renderer.read_pass_output("compose-radiance"));
        // The estimators differ where it is switched on.
        const FloatImage raw = renderer.read_pass_output("ao-raw");
        CHECK(*std::min_element(raw.pixels.begin(), raw.pixels.end()) < 0.9f);
    }
    REQUIRE(composed[0].pixels.size() == composed[1].pixels.size());
    CHECK(composed[0].pixels == composed[1].pixels);
}

}  // namespace
}  // namespace deepgi::test
