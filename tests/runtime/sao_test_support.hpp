#pragma once
// Shared by the deep SAO test files: tiny scenes built in the test (so each
// expectation can be worked out by hand), tap patterns and kernels other than
// the build's, and read-back helpers.
#include "deepgi/context.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/scene_builder.hpp"
#include "support/runtime_support.hpp"

#include <spiral/codegen.hpp>
#include <spiral/optimizer.hpp>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <unistd.h>

namespace deepgi::test {

inline void write_ao_header(const std::filesystem::path& dir, int taps, int tau) {
    spiral::codegen::write_file_atomically(
        dir / "ao_taps.glsl", spiral::codegen::make_gather_header("ao", taps, tau, {"sao test"}));
}

inline void write_blur_header(const std::filesystem::path& dir, int radius,
                              std::optional<double> sigma = std::nullopt) {
    spiral::codegen::write_file_atomically(
        dir / "blur_kernel.glsl",
        spiral::codegen::format_blur_header(spiral::codegen::gaussian_kernel(radius, sigma),
                                            {"sao test"}));
}

// The pattern of the build-time ao_taps.glsl, asked of the codegen library.
inline std::vector<spiral::codegen::Tap> build_time_ao_taps() {
    const int taps = SAO_TEST_AO_TAPS;
    const int tau = SAO_TEST_AO_TAU != 0 ? SAO_TEST_AO_TAU : spiral::search(taps).tau;
    return spiral::codegen::spiral_taps(taps, tau);
}

inline RenderSettings small_settings(int width, int height) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.shadow_map_size = 64;
    return settings;
}

inline Camera camera_at_origin(float fov_degrees = 60.0f, float near_plane = 0.05f) {
    Camera camera;
    camera.vertical_fov = glm::radians(fov_degrees);
    camera.near_plane = near_plane;
    return camera;  // at the origin, looking down -Z
}

// A white quad facing +Z at z = -distance, wide enough to fill any view.
inline Scene camera_facing_plane(float distance) {
    Scene scene;
    scene.name = "test-plane";
    SceneBuilder builder;
    const int white = builder.add_material({0.8f, 0.8f, 0.8f});
    const float extent = 100.0f * distance;
    builder.add_quad({-extent, -extent, -distance}, {extent, -extent, -distance},
                     {extent, extent, -distance}, {-extent, extent, -distance}, {0, 0, 1}, white);
    builder.finish(scene);
    scene.default_camera = camera_at_origin();
    scene.camera_path.keys = {scene.default_camera};
    return scene;
}

// A floor (y = -1) under a camera at the origin, with a wall and blocks on it,
// some boxes hidden behind others so layer 1 has surfaces to offer; optionally
// a quad just beyond the near plane.
inline Scene occluded_floor(bool with_near_quad = false) {
    Scene scene;
    scene.name = "test-floor";
    SceneBuilder builder;
    const int white = builder.add_material({0.8f, 0.8f, 0.8f});
    builder.add_quad({-20, -1, 5}, {20, -1, 5}, {20, -1, -40}, {-20, -1, -40}, {0, 1, 0}, white);
    builder.add_quad({-20, -1, -6}, {20, -1, -6}, {20, 6, -6}, {-20, 6, -6}, {0, 0, 1}, white);
    builder.add_box({-0.8f, -0.4f, -3.0f}, {0.5f, 0.6f, 0.5f}, white, 0.3f);
    builder.add_box({-0.8f, -0.7f, -4.2f}, {0.3f, 0.3f, 0.3f},
                    white);  // partly behind the first box
    builder.add_box({1.2f, -0.2f, -4.0f}, {0.3f, 0.8f, 0.3f}, white, -0.5f);
    builder.add_box({1.0f, -0.8f, -5.0f}, {0.6f, 0.2f, 0.4f}, white);
    if (with_near_quad) {
        builder.add_quad({-0.2f, -0.2f, -0.06f}, {0.1f, -0.2f, -0.06f}, {0.1f, 0.1f, -0.051f},
                         {-0.2f, 0.1f, -0.051f}, {0, 0, 1}, white);
    }
    builder.finish(scene);
    scene.default_camera = camera_at_origin();
    scene.default_camera.pitch = glm::radians(-15.0f);
    scene.camera_path.keys = {scene.default_camera};
    return scene;
}

}  // namespace deepgi::test
