// The frame_statistics pass against the formulas, evaluated here on images
// read back from the renderer: the log-average luminance of the lit
// surfaces (exp of the mean of log(1e-4 + Y), Y the Rec. 709 luminance of
// compose-radiance, over the viewport pixels where layer 0 holds a
// surface), the auto exposure key / log-average with its clamp and its
// smoothing, each layer's depth range against the dumped depths, and the
// depth debug views scaled by it.
#include "deepgi/context.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene_builder.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

using namespace deepgi;

namespace {

RenderSettings small_settings(float exposure) {
    RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.shadow_map_size = 256;
    settings.exposure = exposure;
    return settings;
}

// exp(mean(log(1e-4 + Y))) over the viewport's surface pixels, in double.
double log_average(const FloatImage& radiance, const FloatImage& depth, int guard, int width,
                   int height) {
    double sum = 0.0;
    long pixels = 0;
    for (int y = guard; y < guard + height; ++y) {
        for (int x = guard; x < guard + width; ++x) {
            if (depth.at(x, y) <= 0.0f) continue;
            const double luminance = 0.2126 * radiance.at(x, y, 0) + 0.7152 * radiance.at(x, y, 1) +
                                     0.0722 * radiance.at(x, y, 2);
            sum += std::log(1e-4 + std::max(luminance, 0.0));
            ++pixels;
        }
    }
    REQUIRE(pixels > 0);
    return std::exp(sum / double(pixels));
}

double clamped_auto_exposure(double log_average) {
    return std::clamp(0.0923 / log_average, 1.0 / 16.0, 16.0);
}

// A wall of one emitted radiance filling the view: black albedo and no
// light, so the composed radiance is the emission at every pixel.
Scene uniform_wall(float radiance) {
    Scene scene;
    scene.name = "uniform wall";
    SceneBuilder builder;
    const int material = builder.add_material(glm::vec3(0.0f), glm::vec3(radiance));
    builder.add_quad({-20, -20, -2}, {20, -20, -2}, {20, 20, -2}, {-20, 20, -2}, {0, 0, 1},
                     material);
    builder.finish(scene);
    scene.key_light.intensity = 0.0f;
    scene.ambient = glm::vec3(0.0f);
    scene.default_camera.position = {0.0f, 0.0f, 0.0f};
    scene.camera_path.keys = {scene.default_camera};
    return scene;
}

}  // namespace

TEST_CASE(
    "frame statistics: the log-average luminance and the first auto exposure equal the "
    "formula on the read-back image",
    "[runtime][frame_statistics]") {
    HeadlessContext context;
    // Atrium has sky (a background the average leaves out) and sunlit stone.
    for (const std::string name : {"cornell", "atrium", "warehouse"}) {
        const Scene scene = make_builtin_scene(name);
        const RenderSettings settings = small_settings(auto_length);
        Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
        renderer.render(scene.default_camera);
        const FrameStatistics statistics = renderer.frame_statistics();
        const double expected =
            log_average(renderer.read_pass_output("compose-radiance"),
                        renderer.read_pass_output("gbuffer-depth-layer0"), renderer.layout().guard,
                        settings.width, settings.height);
        INFO(name << ": log-average " << statistics.log_average_luminance << ", expected "
                  << expected << "; exposure " << statistics.exposure);
        CHECK(statistics.log_average_luminance == Approx(expected).epsilon(1e-4));
        // The first frame after a new renderer has no history: exact.
        CHECK(statistics.exposure == Approx(clamped_auto_exposure(expected)).epsilon(1e-4));
        CHECK(statistics.exposure == renderer.exposure_in_use());
    }
}

TEST_CASE("frame statistics: a uniform radiance L gets the exposure key / L, clamped to [1/16, 16]",
          "[runtime][frame_statistics]") {
    HeadlessContext context;
    // 0.5 and 2 are exact in the composed image's 11- and 10-bit floats.
    for (const float radiance : {0.5f, 0.125f, 0.0f, 100.0f}) {
        const Scene scene = uniform_wall(radiance);
        Renderer renderer(scene, small_settings(auto_length),
                          ShaderLoader::from_build_configuration());
        renderer.render(scene.default_camera);
        const double log_average = 1e-4 + radiance;
        const double expected = clamped_auto_exposure(log_average);
        INFO("radiance " << radiance << ": exposure " << renderer.exposure_in_use() << ", expected "
                         << expected);
        CHECK(renderer.frame_statistics().log_average_luminance ==
              Approx(log_average).epsilon(1e-5));
        CHECK(renderer.exposure_in_use() == Approx(expected).epsilon(1e-5));
    }
    // The clamp's two ends, as the table above reaches them.
    CHECK(clamped_auto_exposure(1e-4) == 16.0);
    CHECK(clamped_auto_exposure(100.0001) == 1.0 / 16.0);
}

TEST_CASE(
    "frame statistics: the auto exposure moves a tenth of the way in log space per frame, "
    "converges for a still camera and restarts exactly after a cut",
    "[runtime][frame_statistics]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    Renderer renderer(scene, small_settings(auto_length), ShaderLoader::from_build_configuration());
    renderer.render(scene.default_camera);
    double previous = renderer.exposure_in_use();
    CHECK(previous == renderer.frame_statistics().auto_exposure_target);
    // A 16 times brighter light keeps history: the exposure follows over frames.
    KeyLight light = renderer.key_light();
    light.intensity *= 16.0f;
    renderer.set_key_light(light);
    double last_step = 0.0;
    for (int frame = 1; frame <= 60; ++frame) {
        renderer.render(scene.default_camera);
        const FrameStatistics statistics = renderer.frame_statistics();
        const double expected =
            std::exp(std::log(previous) + 0.1 * (std::log(double(statistics.auto_exposure_target)) -
                                                 std::log(previous)));
        INFO("frame " << frame << ": exposure " << statistics.exposure << ", target "
                      << statistics.auto_exposure_target << ", expected " << expected);
        REQUIRE(statistics.exposure == Approx(expected).epsilon(1e-5));
        if (frame == 1) REQUIRE(statistics.exposure < 0.9 * previous);  // it does move
        last_step = std::abs(statistics.exposure - previous) / previous;
        previous = statistics.exposure;
    }
    // Still camera: a fixed value, within 1% of the target after 60 frames
    // (0.9^60 = 0.2% of the step left; the rest is the lag behind a target
    // that moves while the temporal filters take in the brighter light:
    // 0.64% measured).
    CHECK(last_step < 1e-3);
    CHECK(previous == Approx(renderer.frame_statistics().auto_exposure_target).epsilon(1e-2));
    // A cut drops history: the first frame after it is exact again.
    renderer.render(camera_on_path(scene.camera_path, 10), CameraMotion::cut);
    CHECK(renderer.exposure_in_use() == renderer.frame_statistics().auto_exposure_target);
}

TEST_CASE(
    "frame statistics: each layer's depth range is the dumped depth's, and the depth views "
    "use the whole ramp",
    "[runtime][frame_statistics]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    for (const int layer : {0, 1}) {
        RenderSettings settings = small_settings(1.0f);
        settings.view = layer == 0 ? DebugView::depth_layer0 : DebugView::depth_layer1;
        Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
        renderer.render(scene.default_camera);
        const int guard = renderer.layout().guard;
        const FloatImage depth =
            renderer.read_pass_output(layer == 0 ? "gbuffer-depth-layer0" : "gbuffer-depth-layer1");
        double nearest = std::numeric_limits<double>::infinity(), farthest = 0.0;
        for (int y = 0; y < settings.height; ++y) {
            for (int x = 0; x < settings.width; ++x) {
                const double z = depth.at(x + guard, y + guard);
                if (z <= 0.0) continue;
                nearest = std::min(nearest, z);
                farthest = std::max(farthest, z);
            }
        }
        REQUIRE(farthest > nearest);
        const DepthRange range = renderer.depth_ranges()[std::size_t(layer)];
        INFO("layer " << layer << ": range " << range.near_depth << " to " << range.far_depth
                      << " m, dumped " << nearest << " to " << farthest);
        CHECK(range.near_depth == Approx(nearest).epsilon(1e-5));
        CHECK(range.far_depth == Approx(farthest).epsilon(1e-5));
        // The view: 1 - 0.9 (z - near) / (far - near) on the display, 0 where
        // the layer is empty.
        const FloatImage view = renderer.read_pass_output("debug_view-colour");
        double lowest = 1.0, highest = 0.0, worst = 0.0;
        for (int y = 0; y < settings.height; ++y) {
            for (int x = 0; x < settings.width; ++x) {
                const double z = depth.at(x + guard, y + guard);
                const double expected =
                    z > 0.0 ? 1.0 - 0.9 * (z - nearest) / (farthest - nearest) : 0.0;
                worst = std::max(worst, std::abs(view.at(x, y, 0) - expected));
                if (z <= 0.0) continue;
                lowest = std::min(lowest, double(view.at(x, y, 0)));
                highest = std::max(highest, double(view.at(x, y, 0)));
            }
        }
        INFO("view values span " << lowest << " to " << highest << ", largest difference "
                                 << worst);
        // 8 bits, and the sRGB decode and encode around them.
        CHECK(worst <= 2.0 / 255.0);
        CHECK(highest - lowest > 0.5);
    }
}
