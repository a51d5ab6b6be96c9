// The delay and predict generators (one pass with a third layer drawn by the
// next frame's camera) against peel, the two-pass oracle that needs no
// history: delay along each scene's camera path, predict along a path of
// constant velocity and after its history is dropped, and the memory their
// third layer adds.
#include "../support/process.hpp"
#include "deepgi/context.hpp"
#include "deepgi/frame_limits.hpp"
#include "deepgi/renderer.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace deepgi;

namespace {

RenderSettings small_settings(Generator generator) {
    RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.generator = generator;
    settings.min_separation = 0.5f;
    settings.shadow_map_size = 512;
    // The G-buffer is what is compared; the spiral estimator, about 5x
    // cheaper than the march on llvmpipe, keeps the frames short.
    settings.ao.method = AoMethod::solid_angle;
    return settings;
}

struct Comparison {
    std::size_t presence = 0;  // pixels present in one image and not the other
    std::size_t values = 0;    // present in both, values beyond the tolerance
};

// `relative`: 0 asks for bit-for-bit equality.
Comparison compare(const FloatImage& actual, const FloatImage& expected, float relative) {
    REQUIRE(actual.pixels.size() == expected.pixels.size());
    Comparison result;
    for (std::size_t i = 0; i < actual.pixels.size(); ++i) {
        const float a = actual.pixels[i], e = expected.pixels[i];
        if ((a == 0.0f) != (e == 0.0f))
            ++result.presence;
        else if (std::abs(a - e) > relative * std::max(std::abs(a), std::abs(e)))
            ++result.values;
    }
    return result;
}

// Layers 0 and 1 of `generator` equal peel's bit for bit at every frame from
// `first_exact` on: depth, normals and albedo, presence included. (Every
// generator draws its layers through the same vertex stage as peel, with no
// geometry shader, for this: gbuffer.vert.) It returns how many layer-1 pixels `previous` got wrong
// on those frames, the evidence that the path moves enough for the comparison to mean something.
std::size_t check_against_peel(const Scene& scene, Generator generator,
                               const std::vector<Camera>& cameras, int first_exact) {
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    Renderer peel(scene, small_settings(Generator::peel), loader);
    Renderer tested(scene, small_settings(generator), loader);
    Renderer previous(scene, small_settings(Generator::previous), loader);
    std::size_t previous_wrong = 0;
    for (int frame = 0; frame + 1 < int(cameras.size()); ++frame) {
        peel.render(cameras[frame]);
        tested.render(cameras[frame], cameras[frame + 1]);
        previous.render(cameras[frame]);
        if (frame == 0) {
            // No prediction yet, so no layer 1, as for previous and reproject.
            const FloatImage first = tested.read_pass_output("gbuffer-depth-layer1");
            REQUIRE(std::all_of(first.pixels.begin(), first.pixels.end(),
                                [](float v) { return v == 0.0f; }));
        }
        if (frame < first_exact) continue;
        INFO(to_string(generator) << ", frame " << frame);
        for (const char* output :
             {"gbuffer-depth-layer1", "gbuffer-normal-layer1", "gbuffer-albedo-layer1",
              "gbuffer-depth-layer0", "gbuffer-normal-layer0", "gbuffer-albedo-layer0"}) {
            INFO(output);
            const Comparison c =
                compare(tested.read_pass_output(output), peel.read_pass_output(output), 0.0f);
            CHECK(c.presence == 0);
            CHECK(c.values == 0);
        }
        const FloatImage truth = peel.read_pass_output("gbuffer-depth-layer1");
        const Comparison p =
            compare(previous.read_pass_output("gbuffer-depth-layer1"), truth, 1e-3f);
        previous_wrong += p.presence + p.values;
    }
    return previous_wrong;
}

}  // namespace

TEST_CASE("generator prediction: delay's layer 1 equals peel's along each camera path",
          "[runtime][gbuffer][prediction]") {
    HeadlessContext context;
    for (const std::string scene_name : {"cornell", "atrium", "warehouse"}) {
        INFO(scene_name);
        const Scene scene = make_builtin_scene(scene_name);
        // Frames 10 to 21 of the path: moving, and across a key.
        std::vector<Camera> cameras;
        const int start = scene.camera_path.frames_per_key - 14;
        for (int frame = start; frame < start + 13; ++frame)
            cameras.push_back(camera_on_path(scene.camera_path, frame));
        const std::size_t previous_wrong = check_against_peel(scene, Generator::delay, cameras, 1);
        CHECK(previous_wrong > 0);  // the path moves: the last frame's layer 0 is wrong
    }
}

TEST_CASE("generator prediction: delay's third layer is the next frame's layer 0",
          "[runtime][gbuffer][prediction]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("atrium");
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    Renderer delay(scene, small_settings(Generator::delay), loader);
    Renderer peel(scene, small_settings(Generator::peel), loader);
    const Camera now = camera_on_path(scene.camera_path, 5);
    const Camera next = camera_on_path(scene.camera_path, 6);
    delay.render(now, next);
    peel.render(next);
    // Bit for bit: the third layer's positions are computed as the next
    // frame's layer 0 will compute them (gbuffer.vert).
    const Comparison c = compare(delay.read_pass_output("gbuffer-depth-prediction"),
                                 peel.read_pass_output("gbuffer-depth-layer0"), 0.0f);
    CHECK(c.presence == 0);
    CHECK(c.values == 0);
    // Only delay and predict have the third layer.
    const std::vector<std::string> names = peel.pass_output_names();
    CHECK(std::find(names.begin(), names.end(), "gbuffer-depth-prediction") == names.end());
}

TEST_CASE("generator prediction: predict's layer 1 equals peel's on a constant-velocity path",
          "[runtime][gbuffer][prediction]") {
    HeadlessContext context;
    for (const std::string scene_name : {"cornell", "atrium", "warehouse"}) {
        INFO(scene_name);
        const Scene scene = make_builtin_scene(scene_name);
        // Steps of powers of two from dyadic starting points: every camera of
        // the path and every extrapolation current + (current - previous) is
        // exact in float, so the predicted camera is the path's next camera
        // to the bit. A lateral step of 1/32 of the bounding radius rounded
        // to a power of two and a yaw of 2^-6 rad per frame.
        const Camera base = scene.default_camera;
        const float radius = scene_bounding_radius(scene);
        const float step = std::exp2(std::round(std::log2(radius / 32.0f)));
        auto dyadic = [](float v) { return std::round(v * 64.0f) / 64.0f; };
        const glm::vec3 start{dyadic(base.position.x), dyadic(base.position.y),
                              dyadic(base.position.z)};
        std::vector<Camera> cameras;
        for (int k = 0; k < 9; ++k) {
            Camera camera = base;
            camera.position = start + glm::vec3(float(k) * step, 0.0f, 0.0f);
            camera.yaw = dyadic(base.yaw) + float(k) * 0.015625f;
            camera.pitch = dyadic(base.pitch);
            cameras.push_back(camera);
        }
        // Frame 1 peels against frame 0's prediction, which had no velocity
        // to extrapolate (still camera); from frame 2 on the prediction is exact.
        const std::size_t previous_wrong =
            check_against_peel(scene, Generator::predict, cameras, 2);
        CHECK(previous_wrong > 0);
    }
}

TEST_CASE("generator prediction: the extrapolated camera keeps velocity and turns the short way",
          "[runtime][prediction]") {
    Camera a, b;
    a.position = {1.0f, 2.0f, 3.0f};
    b.position = {1.5f, 2.0f, 2.0f};
    a.yaw = 3.0f;
    b.yaw = -3.0f;  // crossed +-pi: a step of 2 pi - 6 rad, not -6
    a.pitch = 0.25f;
    b.pitch = 0.5f;
    const Camera next = extrapolate_camera(a, b);
    CHECK(next.position == glm::vec3(2.0f, 2.0f, 1.0f));
    CHECK(next.yaw == Approx(-3.0f + (6.2831853f - 6.0f)).margin(1e-5));
    CHECK(next.pitch == 0.75f);
    b.pitch = 1.5f;  // kept short of straight up
    CHECK(extrapolate_camera(a, b).pitch <= 1.55f);
}

TEST_CASE("generator prediction: the memory estimate counts the third layer",
          "[runtime][prediction][limits]") {
    RenderSettings settings;
    settings.width = 1280;
    settings.height = 720;
    const FrameLayout layout = frame_layout(settings);
    const std::uint64_t internal =
        std::uint64_t(layout.internal_width) * std::uint64_t(layout.internal_height);
    settings.generator = Generator::peel;
    const std::uint64_t peel = estimate_frame_bytes(settings);
    // The formats gbuffer_pass.cpp allocates, one more array layer each:
    // depth 32F, normal RG16F, albedo RGBA8, emissive R11G11B10F, motion RGBA16F.
    const std::uint64_t third_layer = 4 + 4 + 4 + 4 + 8;
    for (Generator generator : {Generator::delay, Generator::predict}) {
        settings.generator = generator;
        CHECK(estimate_frame_bytes(settings) == peel + third_layer * internal);
    }
    for (Generator generator : {Generator::previous, Generator::reproject}) {
        settings.generator = generator;
        CHECK(estimate_frame_bytes(settings) == peel);
    }
    // On the command line: a budget peel fits in and delay does not.
    const std::uint64_t mib = 1 << 20;
    const std::uint64_t budget = (peel + mib - 1) / mib;
    settings.generator = Generator::delay;
    REQUIRE(estimate_frame_bytes(settings) > budget * mib);
    for (const char* generator : {"delay", "predict"}) {
        const auto result = spiral::test::run_command(
            fmt::format("{} --headless --generator {} --size 1280x720 --max-gpu-memory {} --output "
                        "/nonexistent-dir/x.png",
                        DEEPGI_EXECUTABLE, generator, budget));
        INFO(result.err);
        CHECK(result.status == 2);
        CHECK(result.err.find("--max-gpu-memory") != std::string::npos);
        CHECK(std::count(result.err.begin(), result.err.end(), '\n') == 1);
    }
}

TEST_CASE("generator prediction: moving to or from delay reallocates and drops history",
          "[runtime][prediction]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    Renderer renderer(scene, small_settings(Generator::peel),
                      ShaderLoader::from_build_configuration());
    renderer.render(scene.default_camera);
    renderer.set_settings(small_settings(Generator::delay));
    REQUIRE(!renderer.history_valid());
    REQUIRE(renderer.history_log().back().find("generator peel -> delay") != std::string::npos);
    renderer.render(scene.default_camera, scene.default_camera);
    renderer.render(scene.default_camera, scene.default_camera);
    // Still camera: the prediction is this frame's layer 0, so layer 1 exists.
    const FloatImage layer1 = renderer.read_pass_output("gbuffer-depth-layer1");
    CHECK(
        std::any_of(layer1.pixels.begin(), layer1.pixels.end(), [](float v) { return v > 0.0f; }));
    // delay -> predict keeps the third layer and the history.
    renderer.set_settings(small_settings(Generator::predict));
    CHECK(renderer.history_valid());
}

TEST_CASE("generator prediction: after a cut or a resize predict starts from a still camera",
          "[runtime][gbuffer][prediction]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("atrium");
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const CameraPath& path = scene.camera_path;
    // Moving frames before the history is dropped, so a predictor that kept
    // the camera from before the drop would extrapolate a long, wrong step.
    const Camera before[] = {camera_on_path(path, 3), camera_on_path(path, 4),
                             camera_on_path(path, 5)};
    // Where the history starts again: far along the path.
    const Camera after = camera_on_path(path, 2 * path.frames_per_key + 7);
    const Camera after_moved = camera_on_path(path, 2 * path.frames_per_key + 8);
    auto finite = [](const FloatImage& image) {
        return std::all_of(image.pixels.begin(), image.pixels.end(),
                           [](float v) { return std::isfinite(v); });
    };
    for (const bool cut : {true, false}) {
        // The second frame still, and moved: either way it has no earlier
        // prediction than the first frame's, made with no velocity, so its
        // layer 1 peels against the first frame's layer 0 at the same pixel,
        // which is `previous`.
        for (const bool moved : {false, true}) {
            INFO((cut ? "cut" : "resize") << ", second frame " << (moved ? "moved" : "still"));
            Renderer predict(scene, small_settings(Generator::predict), loader);
            Renderer previous(scene, small_settings(Generator::previous), loader);
            for (Renderer* renderer : {&predict, &previous}) {
                for (const Camera& camera : before) renderer->render(camera);
                if (cut) {
                    renderer->render(after, CameraMotion::cut);
                } else {
                    RenderSettings resized = renderer->settings();
                    resized.width = 144;
                    resized.height = 80;
                    renderer->set_settings(resized);
                    REQUIRE(!renderer->history_valid());
                    renderer->render(after);
                }
            }
            // The first frame: no history, no layer 1, as for previous.
            const FloatImage first = predict.read_pass_output("gbuffer-depth-layer1");
            CHECK(std::all_of(first.pixels.begin(), first.pixels.end(),
                              [](float v) { return v == 0.0f; }));
            // Its prediction is this frame's layer 0 (a still camera), bit for bit.
            const Comparison still =
                compare(predict.read_pass_output("gbuffer-depth-prediction"),
                        predict.read_pass_output("gbuffer-depth-layer0"), 0.0f);
            CHECK(still.presence == 0);
            CHECK(still.values == 0);

            const Camera second = moved ? after_moved : after;
            predict.render(second);
            previous.render(second);
            for (const char* output : {"gbuffer-normal-layer1", "gbuffer-albedo-layer1"}) {
                INFO(output);
                const Comparison c = compare(predict.read_pass_output(output),
                                             previous.read_pass_output(output), 0.0f);
                CHECK(c.presence == 0);
                CHECK(c.values == 0);
            }
            // Depth too, bit for bit: both draw their layers as instances
            // through the same vertex stage.
            const FloatImage layer1 = predict.read_pass_output("gbuffer-depth-layer1");
            const Comparison c =
                compare(layer1, previous.read_pass_output("gbuffer-depth-layer1"), 0.0f);
            CHECK(c.presence == 0);
            CHECK(c.values == 0);
            // Layer 1 exists, and nothing is infinite or NaN.
            CHECK(std::any_of(layer1.pixels.begin(), layer1.pixels.end(),
                              [](float v) { return v > 0.0f; }));
            for (const char* output : {"gbuffer-depth-layer0", "gbuffer-depth-layer1",
                                       "gbuffer-depth-prediction", "compose-radiance"}) {
                INFO(output);
                CHECK(finite(predict.read_pass_output(output)));
            }
        }
    }
}
