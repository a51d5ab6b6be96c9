// The renderer's frame: the list of passes in the order they run (one line
// each in passes/pass_list.hpp), the per-frame constants, and the loop that
// resizes and runs the passes over a RendererState (renderer.cpp is the
// Renderer around it).
// Nothing here knows a pass's textures; passes meet in FrameResources.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/settings.hpp"
#include "gl/pass_timer.hpp"
#include "frame_resources.hpp"
#include "pass.hpp"
#include "passes/passes.hpp"
#include "renderer_state.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace deepgi {

namespace shader_shared {
// The shader's own sequence source (shaders/temporal_sequence.h).
using uint = std::uint32_t;
#define DEEPGI_SHARED_FUNCTION inline
#include "temporal_sequence.h"
#undef DEEPGI_SHARED_FUNCTION
}  // namespace shader_shared
using shader_shared::temporal_sequence_u_fixed;
using shader_shared::temporal_sequence_v_fixed;

using shader_shared::FrameConstants;

FrameLayout frame_layout(const RenderSettings& settings) {
    FrameLayout layout;
    layout.guard =
        static_cast<int>(std::lround(settings.guard_band_fraction * float(settings.height)));
    layout.internal_width = settings.width + 2 * layout.guard;
    layout.internal_height = settings.height + 2 * layout.guard;
    return layout;
}

glm::mat4 guard_band_projection(const Camera& camera, const RenderSettings& settings) {
    const FrameLayout layout = frame_layout(settings);
    const float focal = 1.0f / std::tan(camera.vertical_fov * 0.5f);
    const float aspect = float(settings.width) / float(settings.height);
    // The viewport keeps its field of view; the guard band widens the frustum.
    glm::mat4 projection(0.0f);
    projection[0][0] = focal / aspect * float(settings.width) / float(layout.internal_width);
    projection[1][1] = focal * float(settings.height) / float(layout.internal_height);
    projection[2][3] = -1.0f;              // clip w = linear depth
    projection[3][2] = camera.near_plane;  // clip z = near, so stored depth = near / linear depth
    return projection;
}

const std::vector<PassFactory>& default_pass_list() {
    // One line per pass in passes/pass_list.hpp, in the order they run.
    static const std::vector<PassFactory> passes = {
#define DEEPGI_PASS(name) make_##name##_pass,
#include "passes/pass_list.hpp"
#undef DEEPGI_PASS
    };
    return passes;
}

namespace {

void GLAPIENTRY collect_gl_error(GLenum, GLenum type, GLuint, GLenum, GLsizei,
                                 const GLchar* message, const void* user) {
    if (type != GL_DEBUG_TYPE_ERROR) return;
    auto* errors = static_cast<std::vector<std::string>*>(const_cast<void*>(user));
    errors->emplace_back(message);
}

}  // namespace

void install_gl_debug(RendererState& state, bool enabled) {
    if (enabled) {
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(collect_gl_error, &state.gl_errors);
    } else {
        glDebugMessageCallback(nullptr, nullptr);
    }
}

namespace {

// With --gl-debug, turns the errors the callback collected into an exception.
void throw_gl_errors(RendererState& state, std::string_view where) {
    if (state.gl_errors.empty()) return;
    const std::string first = state.gl_errors.front();
    const std::size_t count = state.gl_errors.size();
    state.gl_errors.clear();
    throw GraphicsError(fmt::format("GL error in {}: {}{}", where, first,
                                    count > 1 ? fmt::format(" (and {} more)", count - 1) : ""));
}

}  // namespace

void resize_passes(RendererState& state) {
    FrameResources& frame = state.frame;
    frame.settings = &state.in_use;
    frame.scene = &state.scene;
    frame.scene_gpu = &state.scene_gpu;
    frame.layout = frame_layout(state.settings);
    frame.empty_vertex_array = state.empty_vertex_array.get();
    frame.allocate_display(state.settings.width, state.settings.height);
    for (auto& pass : state.passes) {
        pass->resize(frame);
        throw_gl_errors(state, fmt::format("resizing pass '{}'", pass->name()));
    }
}

namespace {

// This frame's point of the temporal sequence (shaders/temporal_sequence.h),
// k frames after history was invalidated: (0, 0) on the first frame, then a
// low-discrepancy walk over [0, 1)^2 that never repeats (the Sobol sequence,
// whose first 16, 64 and 256 frames are each stratified over the square), so
// a still camera's running mean keeps receiving new samples of the integral.
// z is the radial shift of the radiosity spiral's taps, frac(1/2 + v) - 1/2
// in [-1/2, 1/2): 0 on the first frame, so a single frame keeps the taps at
// (i + 1/2) / n.
// Taken in fixed point, so it is exact.
glm::vec4 temporal_sample(std::uint32_t k) {
    constexpr float to_unit = 1.0f / 16777216.0f;  // top 24 bits: exact in float
    const auto unit = [&](std::uint32_t fixed) { return float(fixed >> 8u) * to_unit; };
    const std::uint32_t v = temporal_sequence_v_fixed(k);
    return {unit(temporal_sequence_u_fixed(k)), unit(v), unit(v + 0x80000000u) - 0.5f, 0.0f};
}

}  // namespace

namespace {

FrameConstants make_frame_constants(const RendererState& state, const Camera& camera,
                                    const Camera& previous, const Camera& next) {
    const RenderSettings& settings = state.in_use;
    const FrameLayout layout = frame_layout(settings);
    const KeyLight& light = state.scene.key_light;
    const ShadowProjection& shadow = state.frame.shadow;
    FrameConstants constants{};
    constants.view = camera_view_matrix(camera);
    constants.projection = guard_band_projection(camera, settings);
    constants.previous_view = camera_view_matrix(previous);
    constants.previous_view_projection =
        guard_band_projection(previous, settings) * constants.previous_view;
    constants.camera_to_light_clip = shadow.light_view_projection * glm::inverse(constants.view);
    constants.camera_ray_scale = {1.0f / constants.projection[0][0],
                                  1.0f / constants.projection[1][1], camera.near_plane, 0.0f};
    const glm::vec3 direction = glm::normalize(light.direction);
    if (light.kind == LightKind::directional) {
        constants.light_vector = glm::vec4(
            glm::normalize(glm::vec3(constants.view * glm::vec4(-direction, 0.0f))), 0.0f);
    } else {
        constants.light_vector =
            glm::vec4(glm::vec3(constants.view * glm::vec4(light.position, 1.0f)),
                      light.range > 0.0f ? 1.0f / light.range : 0.0f);
    }
    constants.spot_axis = glm::vec4(glm::vec3(constants.view * glm::vec4(direction, 0.0f)),
                                    std::cos(light.outer_cone));
    if (light.kind == LightKind::point)
        constants.spot_axis = glm::vec4(shadow.cube_near, shadow.cube_far, 0.0f, 0.0f);
    constants.light_radiance =
        glm::vec4(light.colour * light.intensity, std::cos(light.inner_cone));
    constants.ambient = glm::vec4(state.scene.ambient, 0.0f);
    constants.background = glm::vec4(state.scene.background, 0.0f);
    constants.internal_size = {float(layout.internal_width), float(layout.internal_height),
                               1.0f / float(layout.internal_width),
                               1.0f / float(layout.internal_height)};
    constants.min_separation = settings.min_separation;
    constants.exposure = settings.exposure;
    constants.shadow_normal_offset = shadow.normal_offset;
    constants.guard_band = layout.guard;
    constants.viewport_width = settings.width;
    constants.viewport_height = settings.height;
    constants.generator = static_cast<int>(settings.generator);
    constants.light_kind = light.kind == LightKind::directional ? DEEPGI_LIGHT_DIRECTIONAL
                           : light.kind == LightKind::spot      ? DEEPGI_LIGHT_SPOT
                                                                : DEEPGI_LIGHT_POINT;
    constants.debug_view = static_cast<int>(settings.view);
    // Which terms compose (and the debug views) add: the frame's decision, so
    // no pass reads another's switches.
    constants.ao_term = settings.ao.enabled ? 1 : 0;
    constants.radiosity_term = settings.radiosity.enabled ? 1 : 0;
    constants.environment_term = settings.environment ? 1 : 0;
    constants.reflection_term = reflections_traced(state.scene, settings) ? 1 : 0;
    // temporal-offset starts the walk at another point: another realisation
    // of every frame's rotation, for measuring run-to-run spread.
    const glm::vec4 sample =
        temporal_sample(state.temporal_frame + std::uint32_t(settings.temporal_offset));
    constants.temporal_frame = int(std::min<std::uint32_t>(state.temporal_frame, INT32_MAX));
    constants.temporal_angle = sample.x * 6.2831853f;
    constants.temporal_sample = sample;
    constants.rotation_seed = settings.rotation_seed;
    constants.next_view = camera_view_matrix(next);
    constants.next_projection = guard_band_projection(next, settings);
    return constants;
}

}  // namespace

bool wants_cpu_clock(TimingMode mode) {
    if (mode == TimingMode::cpu) return true;
    if (mode == TimingMode::gpu) return false;
    return query_context_info().is_software_renderer;
}

void render_frame(RendererState& state, const Camera& camera, const Camera& next_camera,
                  CameraMotion motion) {
    FrameResources& frame = state.frame;
    if (motion == CameraMotion::cut) frame.invalidate_history("camera cut");
    frame.camera = camera;
    if (!frame.history_valid()) {
        frame.previous_camera = camera;
        state.temporal_frame = 0;
    }
    // Predict's next camera continues the motion of the last two frames. The
    // first frame after an invalidation has one camera and so no velocity: it
    // predicts a still camera (this one), and the frame after peels against
    // that, which is what `previous` does.
    const bool predicts = state.in_use.generator == Generator::predict;
    const Camera next = !predicts               ? next_camera
                        : frame.history_valid() ? extrapolate_camera(frame.previous_camera, camera)
                                                : camera;
    const FrameConstants constants =
        make_frame_constants(state, camera, frame.previous_camera, next);
    glNamedBufferSubData(state.frame_constants.get(), 0, sizeof(constants), &constants);
    glBindBufferBase(GL_UNIFORM_BUFFER, DEEPGI_UBO_FRAME, state.frame_constants.get());
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);

    state.timer.begin_frame();
    frame.begin_frame_textures();
    for (std::size_t i = 0; i < state.passes.size(); ++i) {
        Pass* pass = state.passes[i].get();
        if (!pass->enabled(state.in_use)) continue;
        ScopedPass timed(state.timer, std::string(pass->name()));
        // check_pass_declarations() has made sure every read is written.
        const PassDeclaration& declaration = state.declarations[i];
        for (const PassRead& read : declaration.reads)
            if (read.binding != PassRead::unbound)
                glBindTextureUnit(read.binding, frame.texture(read.texture));
        frame.begin_pass(pass->name(), declaration.writes, declaration.value_reads);
        pass->run(frame);
        frame.end_pass();
        throw_gl_errors(state, fmt::format("pass '{}'", pass->name()));
    }
    state.timer.end_frame();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    frame.end_frame();
    state.last_camera = camera;
    state.statistics.reset();
    ++state.temporal_frame;
}

std::map<std::string, float, std::less<>> declared_values(
    const std::vector<PassDeclaration>& declarations) {
    std::map<std::string, float, std::less<>> values;
    for (const PassDeclaration& declaration : declarations)
        for (const PassValue& value : declaration.value_writes) values[value.name] = value.value;
    return values;
}

std::vector<PassOutput> all_outputs(const RendererState& state) {
    std::vector<PassOutput> outputs;
    for (const auto& pass : state.passes) {
        if (!pass->enabled(state.in_use)) continue;
        for (auto& output : pass->outputs(state.frame)) outputs.push_back(std::move(output));
    }
    return outputs;
}

Camera extrapolate_camera(const Camera& previous, const Camera& current) {
    Camera next = current;
    next.position = current.position + (current.position - previous.position);
    // The yaw step the short way round, so a path crossing +-pi keeps turning
    // the way it turned.
    constexpr float pi = 3.14159265358979f;
    float yaw_step = current.yaw - previous.yaw;
    if (yaw_step > pi) yaw_step -= 2.0f * pi;
    if (yaw_step < -pi) yaw_step += 2.0f * pi;
    next.yaw = current.yaw + yaw_step;
    // Kept short of straight up or down, where the view would flip.
    next.pitch = std::clamp(current.pitch + (current.pitch - previous.pitch), -1.55f, 1.55f);
    return next;
}

float scene_bounding_radius(const Scene& scene) {
    const float radius = 0.5f * glm::length(scene.bounds.max - scene.bounds.min);
    // An empty or degenerate scene still gets positive lengths.
    return std::isfinite(radius) && radius > 0.0f ? radius : 1.0f;
}

SceneScale scene_scale(const Scene& scene) {
    const glm::vec3 size = scene.bounds.max - scene.bounds.min;
    const float smallest = std::min({size.x, size.y, size.z});
    return {.bounding_radius = scene_bounding_radius(scene),
            .smallest_extent = std::isfinite(smallest) ? std::max(smallest, 0.0f) : 0.0f};
}

}  // namespace deepgi
