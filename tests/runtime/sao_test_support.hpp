#pragma once
// Shared by the deep SAO test files: tiny scenes built in the test (so each
// expectation can be worked out by hand; test_scenes.hpp), tap patterns and
// kernels other than the build's, read-back helpers, and the cornell
// renderer the temporal and rotation tests begin with.
#include "deepgi/context.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/scene_builder.hpp"
#include "sao_reference.hpp"
#include "support/runtime_support.hpp"
#include "test_scenes.hpp"

#include <spiral/codegen.hpp>
#include <spiral/optimizer.hpp>

#include <fmt/format.h>

#include <algorithm>
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

// What many tests begin with: a GL context, then the cornell scene and a
// renderer of it with `settings` (the renderer keeps its own copies of the
// settings and the shader loader).
struct CornellRenderer {
    explicit CornellRenderer(const RenderSettings& settings)
        : renderer(scene, settings, ShaderLoader::from_build_configuration()) {}
    HeadlessContext context;  // first: the renderer needs it
    const Scene scene = make_builtin_scene("cornell");
    Renderer renderer;
};

// One frame's SAO inputs and outputs, read back for the CPU evaluation.
struct FrameReadBack {
    SaoInputs inputs;
    FloatImage raw;
    FloatImage blurred;
};

inline FrameReadBack render_and_read(const Scene& scene, const RenderSettings& settings,
                                     const ShaderLoader& loader) {
    Renderer renderer(scene, settings, loader);
    renderer.render(scene.default_camera);
    FrameReadBack frame;
    for (int level = 0;; ++level) {
        const std::string name = fmt::format("depth_pyramid-level{}", level);
        const auto names = renderer.pass_output_names();
        if (std::find(names.begin(), names.end(), name) == names.end()) break;
        frame.inputs.pyramid.push_back(renderer.read_pass_output(name));
    }
    frame.inputs.normals = renderer.read_pass_output("gbuffer-normal-layer0");
    frame.inputs.normals_layer1 = renderer.read_pass_output("gbuffer-normal-layer1");
    if (ao_method_reads_back_faces(settings.ao.method)) {
        for (int layer = 0; layer < settings.ao.layers; ++layer)
            frame.inputs.back_faces.push_back(
                renderer.read_pass_output(fmt::format("backface-depth-layer{}", layer)));
    }
    frame.inputs.ray_scale = renderer_ray_scale(scene.default_camera, settings);
    frame.inputs.near_plane = scene.default_camera.near_plane;
    frame.inputs.q = settings.depth_pyramid.q;
    frame.raw = renderer.read_pass_output("ao-raw");
    frame.blurred = renderer.read_pass_output("ao-blurred");
    return frame;
}

}  // namespace deepgi::test
