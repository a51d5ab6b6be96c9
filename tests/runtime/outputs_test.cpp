// Pass outputs: finite everywhere, odd and tiny sizes, direct light against a
// CPU evaluation of the same formula on the same G-buffer inputs, the final
// image against the filmic curve and sRGB encoding written from their formulas.
#include "deepgi/context.hpp"
#include "deepgi/renderer.hpp"
#include "ray_cast_oracle.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

using namespace deepgi;

TEST_CASE("outputs: no NaN or Inf in any pass output, for every scene and generator",
          "[runtime][outputs]") {
    HeadlessContext context;
    for (const std::string scene_name : {"cornell", "atrium", "warehouse"}) {
        const Scene scene = make_builtin_scene(scene_name);
        for (Generator generator : {Generator::peel, Generator::previous, Generator::reproject,
                                    Generator::delay, Generator::predict}) {
            RenderSettings settings;
            settings.width = 160;
            settings.height = 90;
            settings.generator = generator;
            settings.shadow_map_size = 512;
            Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
            for (int frame = 0; frame < 3; ++frame)
                renderer.render(camera_on_path(scene.camera_path, frame * 4),
                                camera_on_path(scene.camera_path, frame * 4 + 4));
            for (const auto& name : renderer.pass_output_names()) {
                INFO(scene_name << " " << to_string(generator) << " " << name);
                REQUIRE(deepgi::test::all_finite(renderer.read_pass_output(name)));
            }
        }
    }
}

TEST_CASE("outputs: odd and tiny sizes render with the right output size", "[runtime][outputs]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    for (auto [width, height] : {std::pair{1, 1}, {3, 2}, {161, 91}}) {
        RenderSettings settings;
        settings.width = width;
        settings.height = height;
        settings.shadow_map_size = 256;
        Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
        renderer.render(scene.default_camera);
        renderer.render(scene.default_camera);
        const auto bytes = renderer.read_output_rgba8();
        REQUIRE(bytes.size() == std::size_t(width) * std::size_t(height) * 4);
        const FloatImage colour = renderer.read_pass_output("tonemap-colour");
        REQUIRE(colour.width == width);
        REQUIRE(colour.height == height);
        const FrameLayout layout = renderer.layout();
        const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
        REQUIRE(depth.width == layout.internal_width);
        REQUIRE(depth.height == layout.internal_height);
        // The centre of the default Cornell view is the back wall or a block.
        REQUIRE(depth.at(layout.internal_width / 2, layout.internal_height / 2) > 1.0f);
        for (const auto& name : renderer.pass_output_names())
            REQUIRE(deepgi::test::all_finite(renderer.read_pass_output(name)));
    }
}

TEST_CASE(
    "outputs: direct light equals albedo/pi * irradiance * cosine where unshadowed (cornell spot)",
    "[runtime][outputs]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.shadow_map_size = 1024;
    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
    renderer.render(scene.default_camera);
    const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
    const FloatImage normal = renderer.read_pass_output("gbuffer-normal-layer0");
    const FloatImage albedo = renderer.read_pass_output("gbuffer-albedo-layer0");
    const FloatImage direct = renderer.read_pass_output("direct_light-radiance-layer0");
    // Camera space from the textbook camera (support/textbook_camera.hpp).
    const deepgi::test::TextbookCamera view =
        deepgi::test::textbook_camera(scene.default_camera, settings);
    const glm::vec3 light_position =
        deepgi::test::textbook_point_to_camera(view, scene.key_light.position);
    const glm::vec3 spot_axis =
        glm::normalize(deepgi::test::textbook_direction_to_camera(view, scene.key_light.direction));
    int checked = 0;
    for (int y = 0; y < depth.height; y += 3) {
        for (int x = 0; x < depth.width; x += 3) {
            const float d = depth.at(x, y);
            if (d <= 0.0f) continue;
            const glm::vec3 ray = deepgi::test::camera_ray(scene.default_camera, settings,
                                                           float(x) + 0.5f, float(y) + 0.5f);
            const glm::vec3 position = ray * d;
            const glm::vec3 n(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
            glm::vec3 to_light = light_position - position;
            const float distance_squared = glm::dot(to_light, to_light);
            to_light = glm::normalize(to_light);
            const float cos_angle = glm::dot(-to_light, spot_axis);
            const float inner = std::cos(scene.key_light.inner_cone);
            if (cos_angle < inner)
                continue;  // outside the cone's flat core: the smoothstep is not modelled here
            const float cosine = std::max(glm::dot(n, to_light), 0.0f);
            for (int c = 0; c < 3; ++c) {
                const float expected = albedo.at(x, y, c) / 3.14159265f *
                                       scene.key_light.colour[c] * scene.key_light.intensity *
                                       cosine / distance_squared;
                const float actual = direct.at(x, y, c);
                // Shadowed pixels can only be darker; lit ones match within R11G11B10F precision.
                REQUIRE(actual <= expected * 1.02f + 1e-3f);
                if (expected > 0.01f && std::abs(actual - expected) <= 0.02f * expected) ++checked;
            }
        }
    }
    REQUIRE(checked > 100);
}

TEST_CASE(
    "outputs: motion vectors equal the CPU reprojection of layer-0 points into the previous camera",
    "[runtime][outputs]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("atrium");
    RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.shadow_map_size = 256;
    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
    const Camera previous = camera_on_path(scene.camera_path, 40);
    const Camera current = camera_on_path(scene.camera_path, 41);
    renderer.render(previous);
    renderer.render(current);
    const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
    const FloatImage motion = renderer.read_pass_output("gbuffer-motion-layer0");
    // Both cameras from the textbook formulas (support/textbook_camera.hpp),
    // not the library's matrices the motion pass uses.
    const deepgi::test::TextbookCamera now = deepgi::test::textbook_camera(current, settings);
    const deepgi::test::TextbookCamera before = deepgi::test::textbook_camera(previous, settings);
    int checked = 0;
    float largest = 0.0f;
    for (int y = 0; y < depth.height; y += 2) {
        for (int x = 0; x < depth.width; x += 2) {
            const float d = depth.at(x, y);
            if (d <= 0.0f) continue;
            const glm::vec2 pixel(float(x) + 0.5f, float(y) + 0.5f);
            const glm::vec3 world =
                now.eye + deepgi::test::textbook_to_world(
                              now, deepgi::test::textbook_camera_ray(now, pixel.x, pixel.y) * d);
            const deepgi::test::TextbookProjection seen =
                deepgi::test::textbook_project(before, world);
            if (seen.depth <= 0.0f) continue;
            const glm::vec2 previous_pixel = seen.pixel;
            const glm::vec2 expected = pixel - previous_pixel;
            const glm::vec2 actual(motion.at(x, y, 0), motion.at(x, y, 1));
            INFO("pixel " << x << "," << y << " expected " << expected.x << "," << expected.y
                          << " got " << actual.x << "," << actual.y);
            REQUIRE(glm::length(actual - expected) <= 0.01f * glm::length(expected) + 0.05f);
            largest = std::max(largest, glm::length(expected));
            ++checked;
        }
    }
    REQUIRE(checked > 1000);
    REQUIRE(largest > 0.5f);  // the camera really moved between the frames
}

namespace {

// Hable's filmic curve with the constants of his published operator
// (shoulder 0.15, linear strength 0.50, linear angle 0.10, toe 0.20, toe
// numerator 0.02, toe denominator 0.30, white 11.2, exposure bias 2), and the
// sRGB transfer function of IEC 61966-2-1; written here from those formulas.
double hable(double x) {
    const double a = 0.15, b = 0.50, c = 0.10, d = 0.20, e = 0.02, f = 0.30;
    return (x * (a * x + c * b) + d * e) / (x * (a * x + b) + d * f) - e / f;
}

double srgb_encode(double linear) {
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double display_value(double radiance, double exposure) {
    const double mapped = std::clamp(hable(2.0 * radiance * exposure) / hable(11.2), 0.0, 1.0);
    return srgb_encode(mapped);
}

}  // namespace

TEST_CASE("outputs: the final image is the filmic curve and sRGB encoding of the exposed radiance",
          "[runtime][outputs]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    // auto_length: the exposure the frame_statistics pass measured, as
    // Renderer::exposure_in_use() reports it (frame_statistics_test.cpp
    // checks that value against the log-average).
    for (const float setting : {1.0f, 0.3f, 4.0f, auto_length}) {
        RenderSettings settings;
        settings.width = 96;
        settings.height = 54;
        settings.shadow_map_size = 256;
        settings.exposure = setting;
        // The tonemap alone: the anti-aliasing after it has tests of its own.
        settings.antialias = 0;
        Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
        renderer.render(scene.default_camera);
        const double exposure = renderer.exposure_in_use();
        if (setting != auto_length) REQUIRE(exposure == setting);
        const FloatImage radiance = renderer.read_pass_output("compose-radiance");
        const FloatImage colour = renderer.read_pass_output("tonemap-colour");
        const std::vector<std::uint8_t> bytes = renderer.read_output_rgba8();
        const int guard = renderer.layout().guard;
        REQUIRE(colour.width == settings.width);
        REQUIRE(bytes.size() == std::size_t(settings.width) * settings.height * 4);
        double lowest = 1.0, highest = 0.0, worst = 0.0;
        int worst_code = 0;
        for (int y = 0; y < colour.height; ++y) {
            for (int x = 0; x < colour.width; ++x) {
                for (int c = 0; c < 3; ++c) {
                    const double expected =
                        display_value(radiance.at(x + guard, y + guard, c), exposure);
                    worst = std::max(worst, std::abs(colour.at(x, y, c) - expected));
                    // The 8-bit output (rows bottom to top, as GL reads them).
                    const int code = bytes[(std::size_t(y) * colour.width + x) * 4 + c];
                    worst_code =
                        std::max(worst_code, std::abs(code - int(std::lround(255.0 * expected))));
                    lowest = std::min(lowest, expected);
                    highest = std::max(highest, expected);
                }
            }
        }
        INFO("exposure " << exposure << (setting == auto_length ? " (auto)" : "")
                         << ": largest difference " << worst << ", " << worst_code
                         << " codes; expected values span [" << lowest << ", " << highest << "]");
        // The display target holds 8 bits per channel: half a code of rounding,
        // and a code for float evaluation order.
        CHECK(worst <= 1.5 / 255.0);
        CHECK(worst_code <= 1);
        // Not a comparison of blacks or of clipped whites.
        CHECK(highest - lowest > 0.3);
    }
}
