// Temporal filter of the ambient visibility against its invariants: averaging
// frames of rotated patterns lowers the pixel-to-pixel noise, leaves the mean
// where a single frame puts it, is the running mean of every frame under a
// still camera, and converges to the mean over many more rotations.
#include "sao_test_support.hpp"
#include "support/targets.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace deepgi::test {
namespace {

struct RegionStatistics {
    double mean = 0.0;
    double neighbour_difference = 0.0;  // mean |AV(x+1, y) - AV(x, y)|
    int pairs = 0;
};

// Over cornell's floor (upward normals; the default camera is unrotated, so
// camera space y is world y), away from the guard band.
RegionStatistics floor_statistics(const FloatImage& visibility, const FloatImage& normal,
                                  const FloatImage& depth) {
    RegionStatistics statistics;
    double sum = 0.0;
    int count = 0;
    auto on_floor = [&](int x, int y) {
        return depth.at(x, y, 0) > 0.0f && normal.at(x, y, 1) > 0.99f;
    };
    for (int y = 0; y < visibility.height; ++y) {
        for (int x = 0; x + 1 < visibility.width; ++x) {
            if (!on_floor(x, y)) continue;
            sum += visibility.at(x, y, 0);
            ++count;
            if (!on_floor(x + 1, y)) continue;
            statistics.neighbour_difference +=
                std::abs(visibility.at(x + 1, y, 0) - visibility.at(x, y, 0));
            ++statistics.pairs;
        }
    }
    REQUIRE(statistics.pairs > 500);
    statistics.mean = sum / count;
    statistics.neighbour_difference /= statistics.pairs;
    return statistics;
}

TEST_CASE("ao_temporal: 16 static frames halve the AO's pixel-to-pixel noise and keep its mean",
          "[ao_temporal]") {
    CornellRenderer cornell(small_settings(320, 180));
    Renderer& renderer = cornell.renderer;
    const Camera& camera = cornell.scene.default_camera;
    renderer.render(camera);
    const FloatImage normal = renderer.read_pass_output("gbuffer-normal-layer0");
    const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
    const RegionStatistics one_frame =
        floor_statistics(renderer.read_pass_output("ao-raw"), normal, depth);
    // The filter's output on the first frame is that frame's SAO result.
    CHECK(renderer.read_pass_output("ao-temporal").pixels ==
          renderer.read_pass_output("ao-raw").pixels);
    for (int frame = 1; frame < 16; ++frame) renderer.render(camera);
    const RegionStatistics filtered =
        floor_statistics(renderer.read_pass_output("ao-temporal"), normal, depth);
    WARN("AO over cornell's floor: neighbour difference one frame "
         << one_frame.neighbour_difference << ", after 16 frames " << filtered.neighbour_difference
         << "; mean " << one_frame.mean << " -> " << filtered.mean);
    CHECK(filtered.neighbour_difference <= 0.5 * one_frame.neighbour_difference);
    CHECK(std::abs(filtered.mean - one_frame.mean) <= 0.01);
}

TEST_CASE("ao_temporal: alpha 0 passes the raw SAO result through", "[ao_temporal]") {
    RenderSettings settings = small_settings(160, 90);
    settings.ao.alpha = 0.0f;
    CornellRenderer cornell(settings);
    for (int frame = 0; frame < 3; ++frame) {
        cornell.renderer.render(cornell.scene.default_camera);
        CHECK(cornell.renderer.read_pass_output("ao-temporal").pixels ==
              cornell.renderer.read_pass_output("ao-raw").pixels);
    }
}

// Errors of one visibility image against a converged still render, over the
// viewport's pixels that have a surface.
struct ErrorAgainstStill {
    double mean_absolute = 0.0;
    int large = 0;  // pixels off by more than ghost_threshold
    int pixels = 0;
};

// An error no pixel of a history-free frame should reach through noise alone
// (its tap noise is a few hundredths); a surface's visibility trailing onto
// another reaches it.
constexpr float ghost_threshold = 0.25f;

ErrorAgainstStill error_against(const FloatImage& visibility, const FloatImage& still,
                                const FloatImage& depth, int guard) {
    ErrorAgainstStill error;
    double sum = 0.0;
    for (int y = guard; y < visibility.height - guard; ++y) {
        for (int x = guard; x < visibility.width - guard; ++x) {
            if (!(depth.at(x, y) > 0.0f)) continue;
            const float e = std::abs(visibility.at(x, y) - still.at(x, y));
            sum += e;
            error.large += e > ghost_threshold;
            ++error.pixels;
        }
    }
    error.mean_absolute = sum / std::max(error.pixels, 1);
    return error;
}

// The filter under camera motion against a fresh frame: history moved with
// the camera must lower the noise, and rejected history must leave no more
// badly wrong pixels than a fresh frame has. All four targets are met (hard
// checks); the table goes to ao-temporal-targets.md, printed by the ctest
// entry "deepgi_ao_temporal_targets_missed" (support/targets.hpp).
spiral::test::TargetTable& targets() {
    static spiral::test::TargetTable table("ao-temporal-targets.md", {});
    return table;
}

TEST_CASE(
    "ao_temporal: along a camera path the filtered AO leaves no trail beyond a fresh frame's "
    "error",
    "[ao_temporal]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    for (const std::string name : {"atrium", "warehouse"}) {
        const Scene scene = make_builtin_scene(name);
        const RenderSettings settings = small_settings(160, 90);
        const int guard = frame_layout(settings).guard;
        // The filter's history along 30 frames of the path.
        Renderer moving(scene, settings, loader);
        const int last = 30;
        for (int frame = 0; frame <= last; ++frame)
            moving.render(camera_on_path(scene.camera_path, frame));
        const Camera camera = camera_on_path(scene.camera_path, last);
        // The oracle: the same camera held still for a whole 16 frames, and
        // one history-free frame at it for the noise a frame has anyway.
        Renderer still(scene, settings, loader);
        still.render(camera);
        const FloatImage fresh = still.read_pass_output("ao-temporal");
        for (int frame = 1; frame < 16; ++frame) still.render(camera);
        const FloatImage converged = still.read_pass_output("ao-temporal");
        const FloatImage depth = moving.read_pass_output("gbuffer-depth-layer0");
        REQUIRE(depth.pixels == still.read_pass_output("gbuffer-depth-layer0").pixels);
        const ErrorAgainstStill filtered =
            error_against(moving.read_pass_output("ao-temporal"), converged, depth, guard);
        const ErrorAgainstStill single = error_against(fresh, converged, depth, guard);
        INFO(name << " at path frame " << last << ": against 16 still frames, filtered along the "
                  << "path MAE " << filtered.mean_absolute << ", " << filtered.large
                  << " pixels off by > " << ghost_threshold << "; a fresh frame MAE "
                  << single.mean_absolute << ", " << single.large << " pixels; " << filtered.pixels
                  << " pixels");
        REQUIRE(filtered.pixels > settings.width * settings.height / 4);
        REQUIRE(single.large > 0);
        // Targets: history moved with the camera lowers the noise a fresh
        // frame has, and rejected history leaves no more badly wrong pixels
        // than a fresh frame has.
        targets().check_at_most(name, "MAE, filtered / fresh", "path frame 30",
                                filtered.mean_absolute / single.mean_absolute, 1.0);
        targets().check_at_most(name, "pixels off by > 0.25, filtered / fresh", "path frame 30",
                                double(filtered.large) / double(single.large), 1.0);
    }
    targets().write();
}

TEST_CASE(
    "ao_temporal: under a still camera the AO is the running mean of every frame's SAO and "
    "converges at least as fast as 1/sqrt(frames)",
    "[ao_temporal]") {
    CornellRenderer cornell(small_settings(96, 54));
    Renderer& renderer = cornell.renderer;
    // The oracles: the mean of the raw results of frames 1..n (the running
    // mean) and, as the converged image, the mean of frames 65..320, whose
    // rotations none of the first 64 frames used.
    constexpr int early = 64, late = 256;
    std::vector<double> running, converged;
    std::vector<FloatImage> filtered;  // after 4, 16, 64 frames
    std::size_t running_ok = 0, running_pixels = 0;
    for (int frame = 1; frame <= early + late; ++frame) {
        renderer.render(cornell.scene.default_camera);
        const FloatImage raw = renderer.read_pass_output("ao-raw");
        std::vector<double>& sum = frame <= early ? running : converged;
        sum.resize(raw.pixels.size(), 0.0);
        for (std::size_t i = 0; i < raw.pixels.size(); ++i) sum[i] += raw.pixels[i];
        if (frame == 4 || frame == 16 || frame == early) {
            filtered.push_back(renderer.read_pass_output("ao-temporal"));
            for (std::size_t i = 0; i < raw.pixels.size(); ++i) {
                running_ok += std::abs(filtered.back().pixels[i] - sum[i] / frame) <= 1e-5;
                ++running_pixels;
            }
        }
    }
    // Only pixels with a surface (sky is 1 in every frame).
    const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
    std::vector<double> errors;
    double occlusion = 0.0;
    std::size_t surface = 0;
    for (double& v : converged) v /= late;
    for (std::size_t i = 0; i < converged.size(); ++i) {
        if (depth.pixels[i] <= 0.0f) continue;
        occlusion += 1.0 - converged[i];
        ++surface;
    }
    REQUIRE(surface > converged.size() / 3);
    REQUIRE(occlusion > 0.01 * double(surface));
    for (const FloatImage& image : filtered) {
        double squared = 0.0;
        for (std::size_t i = 0; i < converged.size(); ++i) {
            if (depth.pixels[i] <= 0.0f) continue;
            squared += (image.pixels[i] - converged[i]) * (image.pixels[i] - converged[i]);
        }
        // RMS relative to the mean occlusion, 1 - AV.
        errors.push_back(std::sqrt(squared / double(surface)) / (occlusion / double(surface)));
    }
    WARN(
        "AO RMS error over mean occlusion against the mean of frames 65-320, after 4, 16, 64 "
        "frames: "
        << errors[0] << ", " << errors[1] << ", " << errors[2]);
    CHECK(running_ok == running_pixels);
    // 1/sqrt(frames) gives 0.5 per fourfold and 0.25 from 4 to 64 frames. The
    // sequence's steps can be uneven (the R2 sequence before Sobol measured
    // 0.65 from 4 to 16, 0.31 from 16 to 64; Sobol 0.31 and 0.38), so the
    // fourfold from 4 only has to fall, and the whole span has to keep up
    // with 1/sqrt.
    CHECK(errors[1] <= 0.75 * errors[0]);
    CHECK(errors[2] <= 0.6 * errors[1]);
    CHECK(errors[2] <= 0.3 * errors[0]);
}

}  // namespace
}  // namespace deepgi::test
