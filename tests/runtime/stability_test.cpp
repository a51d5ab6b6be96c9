// Numerical hard cases for the deep G-buffer and deep SAO: the same scene at
// very different scales, far geometry with a tiny near plane, grazing views of
// an open plane, depth discontinuities inside the guard band, and degenerate
// image sizes. docs/deep-sao.md, "Numerical stability".
#include "sao_test_support.hpp"

#include "deepgi/hard_cases.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace deepgi::test {
namespace {

namespace hc = hard_cases;

using Frame = hc::AoFrame;

// Both estimators that ship: the default and the march.
constexpr AoMethod methods[] = {AoMethod::solid_angle, AoMethod::march};

RenderSettings with_method(RenderSettings settings, AoMethod method) {
    settings.ao.method = method;
    settings.ao.bias = default_ao_bias(method);
    return settings;
}

Frame render(const Scene& scene, const RenderSettings& settings, const ShaderLoader& loader) {
    return hc::render_ao(scene, settings, loader);
}

// Finite and at most 1, and at least 0 for the estimators that are not
// signed. The solid-angle visibility is signed before compose clamps it
// (sao.frag, docs/deepgi.md "--dump DIR"), so it has no lower bound here; the
// march's is a share of rays and lies in [0, 1].
void check_valid_visibility(const Frame& frame, AoMethod method) {
    for (const FloatImage* image : {&frame.raw, &frame.blurred}) {
        CHECK(all_finite(*image));
        const auto [low, high] = std::minmax_element(image->pixels.begin(), image->pixels.end());
        CHECK(*high <= 1.0f);
        if (method != AoMethod::solid_angle) CHECK(*low >= 0.0f);
    }
    CHECK(all_finite(frame.depth));
}

// Renders the frame, checks it is valid, and returns its lowest visibility
// over the visible (non-guard) pixels that hit a surface.
float lowest_on_surfaces(const Scene& scene, const RenderSettings& settings,
                         const ShaderLoader& loader, int* surface_pixels) {
    const Frame frame = render(scene, settings, loader);
    check_valid_visibility(frame, settings.ao.method);
    long long count = 0;
    const double lowest = hc::lowest_on_surfaces(frame, frame_layout(settings).guard, &count);
    *surface_pixels = int(count);
    return float(lowest);
}

TEST_CASE("stability: a scene scaled by 1e-3 and by 1e3 with matching lengths gives the same AV",
          "[stability]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const hc::Parameters cases;
    REQUIRE(cases.scale_tolerance <= 1e-3);  // the documented bound, not whatever is shared
    std::vector<std::pair<std::string, AoMethod>> runs;
    for (const std::string& scene : cases.scaled_scenes)
        for (AoMethod method : methods) runs.emplace_back(scene, method);
    for (const auto& [name, method] : runs) {
        const Scene base = make_reference_scene(name);
        const RenderSettings settings =
            with_method(hc::base_settings(cases.width, cases.height), method);
        const Frame unit = render(base, settings, loader);
        int occluded = 0;
        for (float v : unit.raw.pixels) occluded += v < 0.9f;
        CHECK(occluded > int(unit.raw.pixels.size() / 100));  // not a comparison of ones
        for (float s : cases.scales) {
            const Frame scaled =
                render(hc::scaled_scene(base, s), hc::scaled_settings(settings, s), loader);
            check_valid_visibility(scaled, settings.ao.method);
            REQUIRE(scaled.raw.pixels.size() == unit.raw.pixels.size());
            float worst_raw = 0.0f, worst_blurred = 0.0f;
            double sum = 0.0;
            std::size_t beyond = 0;
            for (std::size_t i = 0; i < unit.raw.pixels.size(); ++i) {
                const float e = std::abs(scaled.raw.pixels[i] - unit.raw.pixels[i]);
                worst_raw = std::max(worst_raw, e);
                beyond += e > 1e-3f;
                sum += e;
                worst_blurred = std::max(
                    worst_blurred, std::abs(scaled.blurred.pixels[i] - unit.blurred.pixels[i]));
            }
            INFO(name << " (" << to_string(method) << ") scaled by " << s << ": worst raw "
                      << worst_raw << ", worst blurred " << worst_blurred << ", mean "
                      << sum / double(unit.raw.pixels.size())
                      << ", pixels beyond 1e-3: " << beyond);
            CHECK(worst_raw <= cases.scale_tolerance);
            CHECK(worst_blurred <= cases.scale_tolerance);
            // A power of two scales every float exactly, so nothing may change
            // unless some step mixes in an unscaled length.
            if (s == 1024.0f || s == 1.0f / 1024.0f) CHECK(worst_raw == 0.0f);
        }
    }
}

TEST_CASE("stability: an open floor 1 km away seen through a 1 mm near plane stays unoccluded",
          "[stability]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const hc::Parameters cases;
    REQUIRE(cases.open_surface_min_visibility >= 0.99);
    for (float pitch : cases.far_pitches) {
        // The view's centre ray meets the floor 1 km away.
        const Scene scene = hc::far_floor(pitch);
        for (float radius : cases.far_radii) {
            for (AoMethod method : methods) {
                RenderSettings settings =
                    with_method(hc::base_settings(cases.width, cases.height), method);
                settings.ao.radius = radius;
                int surface = 0;
                const float lowest = lowest_on_surfaces(scene, settings, loader, &surface);
                INFO("pitch " << pitch << ", radius " << radius << ", " << to_string(method)
                              << ": lowest AV " << lowest << " over " << surface
                              << " floor pixels");
                CHECK(surface > cases.width * cases.height / 2);
                CHECK(lowest >= cases.open_surface_min_visibility);
            }
        }
    }
}

TEST_CASE("stability: an open plane seen at grazing angles keeps AV >= 0.99", "[stability]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const hc::Parameters cases;
    REQUIRE(cases.open_surface_min_visibility >= 0.99);
    for (float pitch : cases.grazing_pitches) {
        const Scene scene = hc::grazing_floor(pitch);
        for (int layers : cases.layers) {
            for (AoMethod method : methods) {
                RenderSettings settings =
                    with_method(hc::base_settings(cases.width, cases.height), method);
                settings.ao.layers = layers;
                int surface = 0;
                const float lowest = lowest_on_surfaces(scene, settings, loader, &surface);
                INFO("pitch " << pitch << ", " << layers << " layer(s), " << to_string(method)
                              << ": lowest AV " << lowest << " over " << surface
                              << " floor pixels");
                CHECK(surface > 0);
                CHECK(lowest >= cases.open_surface_min_visibility);
            }
        }
    }
}

TEST_CASE(
    "stability: depth discontinuities inside the guard band give finite AV, in [0, 1] "
    "for the march and at most 1 for the signed solid angle",
    "[stability]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const hc::Parameters cases;
    const RenderSettings base = hc::base_settings(cases.width, cases.height);
    const FrameLayout layout = frame_layout(base);
    REQUIRE(layout.guard > 2);
    // A near wall whose edge crosses the guard band of the left side, in front
    // of a far one: depth jumps from 0.3 m to 50 m between neighbouring pixels
    // in the guard band, right where the visible frame begins, and next to it.
    const std::vector<int> edges = hc::guard_edge_columns(base);
    REQUIRE(edges.front() < 0);
    std::vector<std::pair<float, AoMethod>> runs;
    for (float radius : cases.guard_radii)
        for (AoMethod method : methods) runs.emplace_back(radius, method);
    for (int edge_px : edges) {
        const Scene scene = hc::guard_edge(base, edge_px);
        for (int layers : cases.layers) {
            for (const auto& [radius, method] : runs) {
                RenderSettings settings = with_method(base, method);
                settings.ao.layers = layers;
                settings.ao.radius = radius;
                const Frame frame = render(scene, settings, loader);
                INFO("edge at visible pixel " << edge_px << ", " << layers << " layer(s), radius "
                                              << radius << ", " << to_string(method));
                check_valid_visibility(frame, method);
                // The discontinuity is really there, in the row's guard band.
                const int y = frame.depth.height / 2;
                const float left = frame.depth.at(0, y, 0);
                const float right = frame.depth.at(frame.depth.width - 1, y, 0);
                CHECK(left > 0.0f);
                CHECK(right > 0.0f);
                CHECK(left != right);
            }
        }
    }
}

TEST_CASE("stability: 1x1 and 3x2 images render every output finite", "[stability]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const hc::Parameters cases;
    for (auto [width, height] : cases.tiny_sizes) {
        for (const std::string& name : cases.tiny_scenes) {
            const Scene scene = make_builtin_scene(name);
            const RenderSettings settings = hc::base_settings(width, height);
            Renderer renderer(scene, settings, loader);
            renderer.render(scene.default_camera);
            int checked = 0;
            for (const std::string& output : renderer.pass_output_names()) {
                const FloatImage image = renderer.read_pass_output(output);
                INFO(name << " at " << width << "x" << height << ", output " << output);
                CHECK(image.width >= 1);
                CHECK(image.height >= 1);
                CHECK(all_finite(image));
                ++checked;
            }
            CHECK(checked >= 4);
            // Signed (sao.frag), but never above 1.
            const FloatImage raw = renderer.read_pass_output("ao-raw");
            CHECK(*std::max_element(raw.pixels.begin(), raw.pixels.end()) <= 1.0f);
        }
    }
}

}  // namespace
}  // namespace deepgi::test
