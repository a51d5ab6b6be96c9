// The deep G-buffer against a CPU ray cast of the same triangles, and the
// single-pass generators against peel.
#include "deepgi/context.hpp"
#include "deepgi/renderer.hpp"
#include "ray_cast_oracle.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <map>
#include <iostream>

using namespace deepgi;
using deepgi::test::ray_cast;

namespace {

RenderSettings small_settings(Generator generator) {
    RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.generator = generator;
    settings.min_separation = 0.5f;
    settings.shadow_map_size = 512;
    return settings;
}

bool close_depth(float gpu, float cpu) {
    return std::abs(gpu - cpu) <= 1e-3f * cpu + 1e-4f;
}

// Peel at every `stride`-th pixel: where the ray cast is stable (the same
// triangles a quarter pixel away in each direction), GPU and CPU layers agree.
void check_peel_against_ray_cast(const std::string& scene_name, int stride) {
    HeadlessContext context;
    const Scene scene = make_builtin_scene(scene_name);
    const RenderSettings settings = small_settings(Generator::peel);
    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
    renderer.render(scene.default_camera);
    const FloatImage depth0 = renderer.read_pass_output("gbuffer-depth-layer0");
    const FloatImage depth1 = renderer.read_pass_output("gbuffer-depth-layer1");

    int layer1_pixels = 0;
    for (int y = 0; y < depth0.height; ++y) {
        for (int x = 0; x < depth0.width; ++x) {
            if (depth1.at(x, y) > 0.0f) {
                ++layer1_pixels;
                REQUIRE(depth0.at(x, y) > 0.0f);
                // Stored depth rounds; allow one part in 1e5 of the distance.
                REQUIRE(depth1.at(x, y) >=
                        depth0.at(x, y) + settings.min_separation - 1e-5f * depth1.at(x, y));
            }
        }
    }
    REQUIRE(layer1_pixels >
            depth0.width * depth0.height / 20);  // the scene really has a second layer

    int compared = 0;
    int compared_layer1 = 0;
    int mismatched = 0;
    for (int y = 1; y < depth0.height - 1; y += stride) {
        for (int x = 1; x < depth0.width - 1; x += stride) {
            const float cx = float(x) + 0.5f;
            const float cy = float(y) + 0.5f;
            const auto centre =
                ray_cast(scene, scene.default_camera, settings, cx, cy, settings.min_separation);
            bool stable = true;
            for (auto [dx, dy] :
                 {std::pair{-0.25f, 0.0f}, {0.25f, 0.0f}, {0.0f, -0.25f}, {0.0f, 0.25f}}) {
                const auto near = ray_cast(scene, scene.default_camera, settings, cx + dx, cy + dy,
                                           settings.min_separation);
                if (near.triangle0 != centre.triangle0 || near.triangle1 != centre.triangle1)
                    stable = false;
            }
            if (!stable) continue;
            ++compared;
            const bool layer0_ok = (centre.triangle0 < 0)
                                       ? depth0.at(x, y) == 0.0f
                                       : close_depth(depth0.at(x, y), centre.layer0);
            const bool layer1_ok = (centre.triangle1 < 0)
                                       ? depth1.at(x, y) == 0.0f
                                       : close_depth(depth1.at(x, y), centre.layer1);
            if (centre.triangle1 >= 0) ++compared_layer1;
            if (!layer0_ok || !layer1_ok) {
                ++mismatched;
                UNSCOPED_INFO(fmt::format("pixel ({}, {}): GPU {} / {}, CPU {} / {}", x, y,
                                          depth0.at(x, y), depth1.at(x, y), centre.layer0,
                                          centre.layer1));
            }
        }
    }
    std::cout << fmt::format(
        "{}: peel vs CPU ray cast: {} stable pixels ({} with a layer 1), {} mismatched\n",
        scene_name, compared, compared_layer1, mismatched);
    REQUIRE(compared_layer1 > 20);
    REQUIRE(mismatched == 0);
}

// Every G-buffer output of both layers that --dump writes.
constexpr const char* gbuffer_outputs[] = {"gbuffer-depth-layer0",    "gbuffer-depth-layer1",
                                           "gbuffer-normal-layer0",   "gbuffer-normal-layer1",
                                           "gbuffer-albedo-layer0",   "gbuffer-albedo-layer1",
                                           "gbuffer-emissive-layer0", "gbuffer-motion-layer0"};

// How many values of `actual` differ from `expected` in any bit (presence
// included: a missing surface is 0).
std::size_t bits_differing(const FloatImage& actual, const FloatImage& expected) {
    REQUIRE(actual.pixels.size() == expected.pixels.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < actual.pixels.size(); ++i)
        if (std::memcmp(&actual.pixels[i], &expected.pixels[i], sizeof(float)) != 0) ++differing;
    return differing;
}

}  // namespace

TEST_CASE("gbuffer: peel layer 1 is at least dz behind layer 0 and matches a CPU ray cast: cornell",
          "[runtime][gbuffer]") {
    check_peel_against_ray_cast("cornell", 1);
}

TEST_CASE("gbuffer: peel matches a CPU ray cast: atrium", "[runtime][gbuffer]") {
    check_peel_against_ray_cast("atrium", 2);
}

TEST_CASE("gbuffer: peel matches a CPU ray cast: warehouse", "[runtime][gbuffer]") {
    check_peel_against_ray_cast("warehouse", 5);
}

TEST_CASE(
    "gbuffer: with a static camera, previous and reproject equal peel bit for bit after "
    "two frames",
    "[runtime][gbuffer]") {
    HeadlessContext context;
    for (const std::string scene_name : {"cornell", "atrium", "warehouse"}) {
        const Scene scene = make_builtin_scene(scene_name);
        Renderer peel(scene, small_settings(Generator::peel),
                      ShaderLoader::from_build_configuration());
        peel.render(scene.default_camera);
        for (Generator generator : {Generator::previous, Generator::reproject}) {
            Renderer single(scene, small_settings(generator),
                            ShaderLoader::from_build_configuration());
            single.render(scene.default_camera);
            // The first frame has no previous layer 0, so it has no layer 1 at all.
            const FloatImage first = single.read_pass_output("gbuffer-depth-layer1");
            for (float value : first.pixels) REQUIRE(value == 0.0f);
            single.render(scene.default_camera);
            // Still, the last frame's layer 0 is this frame's, so layer 1 peels
            // against what peel's second pass does; and every layer is drawn
            // through the vertex stage peel uses (one instance per layer, no
            // geometry shader), so the depths agree to the last bit, not only
            // to rounding.
            for (const char* output : gbuffer_outputs) {
                INFO(scene_name << " " << to_string(generator) << " " << output);
                REQUIRE(bits_differing(single.read_pass_output(output),
                                       peel.read_pass_output(output)) == 0);
            }
        }
    }
}

TEST_CASE(
    "gbuffer: along the camera path previous and reproject have peel's layer 0 bit for bit, and "
    "reproject's layer 1 disagrees with peel on fewer pixels than previous's, within each scene's "
    "regression bounds",
    "[runtime][gbuffer]") {
    HeadlessContext context;
    // Regression bounds, not targets: the share of layer-1 pixels disagreeing
    // with peel, measured as in docs/deepgi.md (previous / reproject: cornell
    // 3.06% / 1.24% along the path inside the room, atrium 10.41% / 3.44%, warehouse 33.26%
    // / 21.93%), about 10% above each (and 0.1 point at least), so a generator that gets worse
    // fails even while it stays better than the other.
    const std::map<std::string, std::pair<double, double>> regression_bound_percent = {
        {"cornell", {3.4, 1.37}}, {"atrium", {11.5, 3.8}}, {"warehouse", {36.6, 24.2}}};
    for (const std::string scene_name : {"cornell", "atrium", "warehouse"}) {
        const Scene scene = make_builtin_scene(scene_name);
        Renderer peel(scene, small_settings(Generator::peel),
                      ShaderLoader::from_build_configuration());
        Renderer previous(scene, small_settings(Generator::previous),
                          ShaderLoader::from_build_configuration());
        Renderer reproject(scene, small_settings(Generator::reproject),
                           ShaderLoader::from_build_configuration());
        long disagree_previous = 0;
        long disagree_reproject = 0;
        long total = 0;
        const int frames = 2 * scene.camera_path.frames_per_key;
        for (int frame = 0; frame < frames; ++frame) {
            const Camera camera = camera_on_path(scene.camera_path, frame);
            peel.render(camera);
            previous.render(camera);
            reproject.render(camera);
            if (frame % 6 != 0) continue;
            // Layer 0 never depends on the reference, and all three draw it
            // through the same vertex stage: bit for bit peel's on every
            // compared frame, moving camera included (motion too: the same
            // previous camera).
            for (const char* output :
                 {"gbuffer-depth-layer0", "gbuffer-normal-layer0", "gbuffer-albedo-layer0",
                  "gbuffer-emissive-layer0", "gbuffer-motion-layer0"}) {
                INFO(scene_name << " frame " << frame << " " << output);
                const FloatImage expected = peel.read_pass_output(output);
                CHECK(bits_differing(previous.read_pass_output(output), expected) == 0);
                CHECK(bits_differing(reproject.read_pass_output(output), expected) == 0);
            }
            if (frame == 0) continue;
            const FloatImage truth = peel.read_pass_output("gbuffer-depth-layer1");
            const FloatImage from_previous = previous.read_pass_output("gbuffer-depth-layer1");
            const FloatImage from_reprojection = reproject.read_pass_output("gbuffer-depth-layer1");
            auto differs = [](float a, float b) {
                return std::abs(a - b) > 1e-3f * std::max(a, b);
            };
            for (std::size_t i = 0; i < truth.pixels.size(); ++i) {
                ++total;
                if (differs(from_previous.pixels[i], truth.pixels[i])) ++disagree_previous;
                if (differs(from_reprojection.pixels[i], truth.pixels[i])) ++disagree_reproject;
            }
        }
        const double previous_percent = 100.0 * double(disagree_previous) / double(total);
        const double reproject_percent = 100.0 * double(disagree_reproject) / double(total);
        std::cout << fmt::format(
            "{}: layer-1 pixels disagreeing with peel along the camera path: previous {:.2f}%, "
            "reproject {:.2f}%\n",
            scene_name, previous_percent, reproject_percent);
        REQUIRE(disagree_previous > 0);  // the path really moves
        REQUIRE(disagree_reproject < disagree_previous);
        const auto [previous_bound, reproject_bound] = regression_bound_percent.at(scene_name);
        INFO(scene_name << ": regression bounds previous " << previous_bound << "%, reproject "
                        << reproject_bound << "%");
        CHECK(previous_percent <= previous_bound);
        CHECK(reproject_percent <= reproject_bound);
    }
}
