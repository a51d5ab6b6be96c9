// The radiosity temporal filter: alpha 0, the running mean and convergence
// under a still camera, history along motion vectors, cuts, and finite
// values along a camera path.
#include "radiosity_gather_reference.hpp"
#include "test_scenes.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace deepgi::test {
namespace {

TEST_CASE("radiosity: with alpha 0 the temporal filter returns the raw gather", "[radiosity]") {
    RenderSettings settings = gather_test_settings();
    settings.radiosity.alpha = 0.0f;
    CornellRenderer cornell(settings);
    const auto& keys = cornell.scene.camera_path.keys;
    for (std::size_t frame = 0; frame < 4; ++frame) {
        cornell.renderer.render(keys[frame % keys.size()]);
        for (int layer = 0; layer < 2; ++layer) {
            const FloatImage raw =
                cornell.renderer.read_pass_output(fmt::format("radiosity-raw-layer{}", layer));
            const FloatImage filtered = cornell.renderer.read_pass_output(
                fmt::format("radiosity-irradiance-layer{}", layer));
            INFO("frame " << frame << ", layer " << layer);
            CHECK(max_value(raw) > 0.0f);
            CHECK(filtered.pixels == raw.pixels);
        }
    }
}

// Mean relative change of an output between two frames: sum |after - before|
// over sum |after|.
double relative_change(const FloatImage& before, const FloatImage& after) {
    double change = 0.0, total = 0.0;
    for (std::size_t i = 0; i < after.pixels.size(); ++i) {
        change += std::abs(after.pixels[i] - before.pixels[i]);
        total += std::abs(after.pixels[i]);
    }
    return change / std::max(total, 1e-12);
}

// The taps turned by `angle`: the gather at this frame's extra rotation is
// the gather of these taps (the per-pixel angle and the frame's add).
std::vector<spiral::codegen::Tap> rotated_taps(std::vector<spiral::codegen::Tap> taps,
                                               double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    for (auto& tap : taps) {
        const double x = tap.x, y = tap.y;
        tap.x = float(c * x - s * y);
        tap.y = float(s * x + c * y);
    }
    return taps;
}

// The taps moved outward by `shift` (in [-1/2, 1/2)) of one radial step, as
// docs/design.md's section 1 and docs/radiosity.md state the frame's radial
// shift: tap i at alpha = (i + 1/2 + shift) / n along its own direction.
std::vector<spiral::codegen::Tap> shifted_taps(std::vector<spiral::codegen::Tap> taps,
                                               double shift) {
    const double n = double(taps.size());
    for (std::size_t i = 0; i < taps.size(); ++i) {
        const double alpha = (double(i) + 0.5 + shift) / n;
        const double length = std::hypot(double(taps[i].x), double(taps[i].y));
        taps[i].x = float(taps[i].x / length * alpha);
        taps[i].y = float(taps[i].y / length * alpha);
        taps[i].alpha = float(alpha);
    }
    return taps;
}

// Relative RMS of `e` against `truth` over the pixels where the truth is lit:
// sqrt(sum (e - truth)^2 / sum truth^2), all channels.
double relative_rms(const FloatImage& e, const std::vector<double>& truth) {
    double error = 0.0, total = 0.0;
    for (std::size_t i = 0; i < truth.size(); ++i) {
        error += (double(e.pixels[i]) - truth[i]) * (double(e.pixels[i]) - truth[i]);
        total += truth[i] * truth[i];
    }
    return std::sqrt(error / std::max(total, 1e-30));
}

TEST_CASE("radiosity: under a still camera E is the running mean of every frame's gather",
          "[radiosity]") {
    RenderSettings settings = gather_test_settings();
    settings.radiosity.rho_prop = 0.0f;
    CornellRenderer cornell(settings);
    // The oracle: the plain average of all raw gathers so far (20 frames, far
    // below the cap), each with its own rotation.
    constexpr int frames = 20;
    std::vector<double> mean;
    std::vector<FloatImage> raws;
    for (int frame = 0; frame < frames; ++frame) {
        cornell.renderer.render(cornell.scene.default_camera);
        raws.push_back(cornell.renderer.read_pass_output("radiosity-raw-layer0"));
        const FloatImage& raw = raws.back();
        mean.resize(raw.pixels.size(), 0.0);
        for (std::size_t i = 0; i < raw.pixels.size(); ++i) mean[i] += raw.pixels[i] / frames;
    }
    // No pattern comes back (the rotation used to repeat every 8 frames).
    std::size_t repeated = 0;
    for (int a = 0; a < frames; ++a)
        for (int b = a + 1; b < frames; ++b) repeated += raws[a].pixels == raws[b].pixels;
    CHECK(repeated == 0);
    const FloatImage& first_raw = raws.front();
    const FloatImage e = cornell.renderer.read_pass_output("radiosity-irradiance-layer0");
    std::size_t within = 0, lit = 0, differs_from_one_frame = 0;
    for (std::size_t p = 0; p < e.pixels.size() / 3; ++p) {
        const double scale = std::max({mean[3 * p], mean[3 * p + 1], mean[3 * p + 2]});
        if (scale <= 1e-3) continue;
        ++lit;
        double error = 0.0, from_first = 0.0;
        for (int k = 0; k < 3; ++k) {
            error = std::max(error, std::abs(e.pixels[3 * p + k] - mean[3 * p + k]));
            from_first = std::max(
                from_first, double(std::abs(e.pixels[3 * p + k] - first_raw.pixels[3 * p + k])));
        }
        // Single-float running mean of half-float inputs: rounding only.
        within += error <= 1e-4 * scale;
        differs_from_one_frame += from_first > 0.05 * scale;
    }
    INFO(within << " of " << lit << " lit pixels within 1e-4 of the mean of " << frames
                << " gathers; " << differs_from_one_frame << " differ from frame 1 by > 5%");
    REQUIRE(lit > e.pixels.size() / 3 / 4);
    CHECK(double(within) >= 0.999 * double(lit));
    CHECK(differs_from_one_frame > lit / 10);
}

TEST_CASE(
    "radiosity: under a still camera E converges to the gather's mean over all rotations "
    "and radial shifts, at least as fast as 1/sqrt(frames), and never freezes",
    "[radiosity]") {
    const auto taps = build_time_radiosity_taps();
    RenderSettings settings = small_settings(128, 72);
    settings.shadow_map_size = 512;
    settings.radiosity.rho_prop = 0.0f;  // fixed inputs: the gather's integral is a fixed image
    CornellRenderer cornell(settings);
    cornell.renderer.render(cornell.scene.default_camera);
    // The oracle: the CPU evaluation of the gather on the read-back inputs,
    // averaged over a grid of 32 extra rotations by 16 radial shifts (not the
    // renderer's sequence), which stands for the integral over the disk the
    // taps sweep: the area integral the estimator's weights are made for.
    const GatherInputs inputs =
        read_inputs(cornell.renderer, cornell.scene.default_camera, settings);
    constexpr int rotations = 32, shifts = 16, samples = rotations * shifts;
    std::vector<double> truth;
    for (int j = 0; j < rotations; ++j) {
        const double angle = 6.283185307179586 * (j + 0.5) / rotations;
        for (int k = 0; k < shifts; ++k) {
            const double shift = (k + 0.5) / shifts - 0.5;
            const FloatImage e =
                reference_gather(inputs, shifted_taps(rotated_taps(taps, angle), shift), settings,
                                 0)
                    .first;
            truth.resize(e.pixels.size(), 0.0);
            for (std::size_t i = 0; i < e.pixels.size(); ++i) truth[i] += e.pixels[i] / samples;
        }
    }
    std::vector<double> errors;  // after 1, 4, 16, 64 frames
    FloatImage at_64;
    double change_after_64 = 0.0;
    for (int frame = 1; frame <= 72; ++frame) {
        if (frame > 1) cornell.renderer.render(cornell.scene.default_camera);
        if (frame == 1 || frame == 4 || frame == 16 || frame == 64) {
            const FloatImage e = cornell.renderer.read_pass_output("radiosity-irradiance-layer0");
            errors.push_back(relative_rms(e, truth));
            if (frame == 64) at_64 = e;
        }
        if (frame == 72) {
            change_after_64 = relative_change(
                at_64, cornell.renderer.read_pass_output("radiosity-irradiance-layer0"));
        }
    }
    WARN("relative RMS of E against the mean over "
         << rotations << " rotations x " << shifts
         << " radial shifts after 1, 4, 16, "
            "64 frames: "
         << errors[0] << ", " << errors[1] << ", " << errors[2] << ", " << errors[3]
         << "; mean relative change from frame 64 to 72: " << change_after_64);
    // 1/sqrt(frames) would give 0.5 for each fourfold; the low-discrepancy
    // sequence does at least that well.
    CHECK(errors[1] <= 0.6 * errors[0]);
    CHECK(errors[2] <= 0.6 * errors[1]);
    CHECK(errors[3] <= 0.6 * errors[2]);
    // Still integrating after 64 frames: it moves, by about 1/64 of one
    // frame's deviation per frame.
    CHECK(change_after_64 > 1e-4);
    CHECK(change_after_64 < 0.05);
}

TEST_CASE("radiosity: history follows the motion vectors, and a cut starts fresh", "[radiosity]") {
    RenderSettings settings = gather_test_settings();
    settings.radiosity.rho_prop = 0.0f;
    CornellRenderer cornell(settings);
    const Camera a = cornell.scene.default_camera;
    // Eight still frames from A, then one from B: where B's history is
    // accepted the point moved, so the filter blends E = mix(raw, history,
    // w) with w = min(8 / 9, alpha) = alpha (temporal_accumulation.glsl).
    for (int frame = 0; frame < 8; ++frame) cornell.renderer.render(a);
    const float alpha = settings.radiosity.alpha;
    const FloatImage e_a = cornell.renderer.read_pass_output("radiosity-irradiance-layer0");
    Camera b = a;
    b.position += glm::vec3(0.07f, -0.03f, -0.1f);
    b.yaw += 0.03f;
    cornell.renderer.render(b);
    const FloatImage e_b = cornell.renderer.read_pass_output("radiosity-irradiance-layer0");
    const FloatImage raw_b = cornell.renderer.read_pass_output("radiosity-raw-layer0");
    const FloatImage depth_b = cornell.renderer.read_pass_output("gbuffer-depth-layer0");
    // The oracle for where each point was: B's pixel projected into camera A
    // with the camera matrices (the renderer uses the motion vectors instead).
    const glm::mat4 a_clip = guard_band_projection(a, settings) * camera_view_matrix(a);
    std::size_t followed = 0, candidates = 0, moved = 0;
    for (int y = 2; y < depth_b.height - 2; ++y) {
        for (int x = 2; x < depth_b.width - 2; ++x) {
            if (depth_b.at(x, y, 0) <= 0.0f) continue;
            const glm::vec4 clip =
                a_clip * glm::vec4(world_point(depth_b, b, settings, x, y), 1.0f);
            const glm::vec2 pixel =
                (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(depth_b.width, depth_b.height);
            const int px = int(std::floor(pixel.x));
            const int py = int(std::floor(pixel.y));
            if (px < 2 || py < 2 || px >= depth_b.width - 2 || py >= depth_b.height - 2) continue;
            ++candidates;
            moved += px != x || py != y;
            bool same = true;
            for (int k = 0; k < 3; ++k) {
                const double expected =
                    (1.0 - double(alpha)) * raw_b.at(x, y, k) + double(alpha) * e_a.at(px, py, k);
                same = same &&
                       std::abs(e_b.at(x, y, k) - expected) <= 1e-5 * std::abs(expected) + 1e-7;
            }
            followed += same;
        }
    }
    INFO(followed << " of " << candidates << " pixels blend A's E from the projected pixel; "
                  << moved << " moved");
    REQUIRE(candidates > depth_b.pixels.size() / 2);
    CHECK(moved > candidates / 2);
    CHECK(double(followed) >= 0.9 * double(candidates));
    CHECK(e_b.pixels != raw_b.pixels);

    // A cut drops all history: the filtered E is this frame's raw gather.
    cornell.renderer.render(a, CameraMotion::cut);
    for (int layer = 0; layer < 2; ++layer) {
        INFO("layer " << layer);
        CHECK(
            cornell.renderer.read_pass_output(fmt::format("radiosity-irradiance-layer{}", layer))
                .pixels ==
            cornell.renderer.read_pass_output(fmt::format("radiosity-raw-layer{}", layer)).pixels);
    }
}

TEST_CASE("radiosity: no NaN or Inf along a camera path with fast turns and a cut", "[radiosity]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    for (const std::string scene_name : {"cornell", "atrium"}) {
        const Scene scene = make_builtin_scene(scene_name);
        RenderSettings settings = gather_test_settings();
        settings.radiosity.rho_prop = 1.0f;
        Renderer renderer(scene, settings, loader);
        Camera camera = scene.default_camera;
        for (int frame = 0; frame < 24; ++frame) {
            CameraMotion motion = CameraMotion::continuous;
            if (frame < 8) {
                camera.yaw += 0.6f;  // a fast turn: most of the image disoccluded each frame
                camera.pitch = 0.3f * std::sin(float(frame));
            } else if (frame == 8) {
                camera = scene.camera_path.keys.back();
                motion = CameraMotion::cut;
            } else {
                camera.position += glm::vec3(0.15f, 0.0f, -0.1f);
                camera.yaw -= 0.25f;
            }
            renderer.render(camera, motion);
            for (const char* output :
                 {"radiosity_prepare-radiance-layer0-level0",
                  "radiosity_prepare-radiance-layer1-level2", "radiosity-raw-layer0",
                  "radiosity-irradiance-layer0", "radiosity-irradiance-layer1", "ao-temporal",
                  "compose-radiance"}) {
                INFO(scene_name << ", frame " << frame << ", " << output);
                CHECK(all_finite(renderer.read_pass_output(output)));
            }
        }
    }
}

}  // namespace
}  // namespace deepgi::test
