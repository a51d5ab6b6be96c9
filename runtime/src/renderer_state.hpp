#pragma once
// What a Renderer holds, and the frame's functions that its methods call:
// frame.cpp runs a frame over this state (the pass list, the frame
// constants, the loop), renderer.cpp is the public Renderer around it.
#include "deepgi/renderer.hpp"
#include "deepgi/settings.hpp"
#include "frame_resources.hpp"
#include "gl/pass_timer.hpp"
#include "pass.hpp"
#include "scene/scene_gpu.hpp"

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace deepgi {

struct RendererState {
    Scene scene;
    RenderSettings settings;  // as given: lengths may be auto_length
    RenderSettings in_use;    // `auto` resolved for this scene: what the passes read
    ShaderLoader loader;
    SceneGpu scene_gpu;
    gl::VertexArray empty_vertex_array;
    gl::Buffer frame_constants;
    std::vector<std::unique_ptr<Pass>> passes;
    std::vector<PassDeclaration> declarations;  // per pass, checked for `settings`
    FrameResources frame;
    PassTimer timer{true};
    std::optional<Camera> last_camera;   // converts dumped depth to metres
    std::vector<std::string> gl_errors;  // from the KHR_debug callback (--gl-debug)
    std::uint32_t temporal_frame = 0;    // frames since history was invalidated (wraps at 2^32)
    // The last frame's statistics, read back on the first request after it.
    mutable std::optional<FrameStatistics> statistics;

    RendererState(const Scene& source, const RenderSettings& render_settings,
                  const ShaderLoader& shader_loader)
        : scene(source), settings(render_settings), loader(shader_loader) {}
};

// With `enabled`, GL errors are collected (--gl-debug) and each pass's are
// thrown after it; without, the callback is removed.
void install_gl_debug(RendererState& state, bool enabled);

// Points the frame resources at the current settings and reallocates every
// pass's render targets. Programs are untouched.
void resize_passes(RendererState& state);

// Whether `mode` times the passes with a CPU clock around glFinish (auto:
// on a software renderer).
bool wants_cpu_clock(TimingMode mode);

// One frame: the enabled passes in list order.
void render_frame(RendererState& state, const Camera& camera, const Camera& next_camera,
                  CameraMotion motion);

// The values the enabled passes give each other (PassValue), by name.
std::map<std::string, float, std::less<>> declared_values(
    const std::vector<PassDeclaration>& declarations);

// Every enabled pass's outputs, in pass order.
std::vector<PassOutput> all_outputs(const RendererState& state);

}  // namespace deepgi
