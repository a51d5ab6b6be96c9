// The renderer's frame: the list of passes in the order they run (one line
// each in passes/pass_list.hpp), the per-frame constants, and the loop that
// resizes, runs and dumps the passes.
// Nothing here knows a pass's textures; passes meet in FrameResources.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/settings.hpp"
#include "gl/pass_timer.hpp"
#include "gl/readback.hpp"
#include "frame_resources.hpp"
#include "pass.hpp"
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>
#include <spiral/fileio.hpp>

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

namespace fs = std::filesystem;
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

namespace {

void GLAPIENTRY collect_gl_error(GLenum, GLenum type, GLuint, GLenum, GLsizei,
                                 const GLchar* message, const void* user) {
    if (type != GL_DEBUG_TYPE_ERROR) return;
    auto* errors = static_cast<std::vector<std::string>*>(const_cast<void*>(user));
    errors->emplace_back(message);
}

void install_gl_debug(RendererState& state, bool enabled) {
    if (enabled) {
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(collect_gl_error, &state.gl_errors);
    } else {
        glDebugMessageCallback(nullptr, nullptr);
    }
}

// With --gl-debug, turns the errors the callback collected into an exception.
void throw_gl_errors(RendererState& state, std::string_view where) {
    if (state.gl_errors.empty()) return;
    const std::string first = state.gl_errors.front();
    const std::size_t count = state.gl_errors.size();
    state.gl_errors.clear();
    throw GraphicsError(fmt::format("GL error in {}: {}{}", where, first,
                                    count > 1 ? fmt::format(" (and {} more)", count - 1) : ""));
}

// Points the frame resources at the current settings and reallocates every
// pass's render targets. Programs are untouched.
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

bool wants_cpu_clock(TimingMode mode) {
    if (mode == TimingMode::cpu) return true;
    if (mode == TimingMode::gpu) return false;
    return query_context_info().is_software_renderer;
}

// One frame: the enabled passes in list order.
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

// The values the enabled passes give each other (PassValue), by name.
std::map<std::string, float, std::less<>> declared_values(
    const std::vector<PassDeclaration>& declarations) {
    std::map<std::string, float, std::less<>> values;
    for (const PassDeclaration& declaration : declarations)
        for (const PassValue& value : declaration.value_writes) values[value.name] = value.value;
    return values;
}

// Every enabled pass's outputs, in pass order.
std::vector<PassOutput> all_outputs(const RendererState& state) {
    std::vector<PassOutput> outputs;
    for (const auto& pass : state.passes) {
        if (!pass->enabled(state.in_use)) continue;
        for (auto& output : pass->outputs(state.frame)) outputs.push_back(std::move(output));
    }
    return outputs;
}

}  // namespace

Renderer::Renderer(const Scene& scene, const RenderSettings& settings, const ShaderLoader& loader)
    : Renderer(scene, settings, loader, default_pass_list()) {}

Renderer::Renderer(const Scene& scene, const RenderSettings& settings, const ShaderLoader& loader,
                   const std::vector<PassFactory>& passes)
    : state_(std::make_unique<RendererState>(scene, settings, loader)) {
    validate(settings);
    RendererState& state = *state_;
    state.in_use = resolve_auto_lengths(settings, scene_scale(state.scene));
    state.scene_gpu = upload_scene(state.scene);
    state.empty_vertex_array = gl::create_vertex_array();
    state.frame_constants = gl::create_buffer();
    glNamedBufferStorage(state.frame_constants.get(), sizeof(FrameConstants), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    state.timer = PassTimer(wants_cpu_clock(settings.timing));
    install_gl_debug(state, settings.gl_debug);
    try {
        for (PassFactory make : passes) state.passes.push_back(make(state.loader, state.scene));
        state.declarations = check_pass_declarations(state.passes, state.in_use);
        state.frame.set_values(declared_values(state.declarations));
        resize_passes(state);
    } catch (...) {
        // No destructor runs for a half-built renderer; the callback must not
        // outlive the error list it writes to.
        if (settings.gl_debug) install_gl_debug(state, false);
        throw;
    }
    state.frame.invalidate_history("new scene");
}

Renderer::~Renderer() {
    if (state_->settings.gl_debug) install_gl_debug(*state_, false);
}

void Renderer::render(const Camera& camera, CameraMotion motion) {
    render_frame(*state_, camera, camera, motion);
}

void Renderer::render(const Camera& camera, const Camera& next_camera, CameraMotion motion) {
    render_frame(*state_, camera, next_camera, motion);
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

void Renderer::set_settings(const RenderSettings& settings) {
    validate(settings);
    RendererState& state = *state_;
    // A new internal size (viewport or guard band) leaves no history to keep.
    const bool resized = settings.width != state.settings.width ||
                         settings.height != state.settings.height ||
                         settings.guard_band_fraction != state.settings.guard_band_fraction;
    bool reallocate = resized;
    bool invalidate = resized;
    std::string reason = fmt::format("resize to {}x{}, guard band {}", settings.width,
                                     settings.height, settings.guard_band_fraction);
    // Beyond that, each pass says what a change costs it; the rows that no
    // pass of the list owns (the frame's own) count here.
    auto count = [&](const SettingsChange& change) {
        reallocate = reallocate || change.reallocate;
        if (!change.drop_history.empty() && !invalidate) {
            invalidate = true;
            reason = change.drop_history;
        }
    };
    count(rows_settings_change(state.settings, settings, [&](std::string_view owner) {
        return std::none_of(state.passes.begin(), state.passes.end(),
                            [&](const auto& pass) { return pass->name() == owner; });
    }));
    for (const auto& pass : state.passes) count(pass->settings_change(state.settings, settings));
    const bool retime = settings.timing != state.settings.timing;
    if (settings.gl_debug != state.settings.gl_debug) install_gl_debug(state, settings.gl_debug);
    // Which passes run, and what they read, can change with any setting
    // (the AO method decides whether the back faces are needed).
    const RenderSettings in_use = resolve_auto_lengths(settings, scene_scale(state.scene));
    std::vector<PassDeclaration> declarations = check_pass_declarations(state.passes, in_use);
    state.settings = settings;
    state.in_use = in_use;
    state.declarations = std::move(declarations);
    state.frame.set_values(declared_values(state.declarations));
    if (reallocate) resize_passes(state);
    if (invalidate) state.frame.invalidate_history(reason);
    if (retime) state.timer = PassTimer(wants_cpu_clock(settings.timing));
}

const RenderSettings& Renderer::settings() const {
    return state_->settings;
}

const RenderSettings& Renderer::settings_in_use() const {
    return state_->in_use;
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

void Renderer::set_key_light(const KeyLight& light) {
    auto finite = [](glm::vec3 v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    if (!finite(light.position) || !finite(light.direction) || !finite(light.colour) ||
        !std::isfinite(light.intensity) || !std::isfinite(light.outer_cone) ||
        !std::isfinite(light.inner_cone) || !std::isfinite(light.range)) {
        throw InputError("light: every value must be finite");
    }
    if (light.intensity < 0.0f || glm::any(glm::lessThan(light.colour, glm::vec3(0.0f))))
        throw InputError("light: intensity and colour must be >= 0");
    if (light.range < 0.0f) throw InputError("light: the range must be >= 0 (0: unlimited)");
    if (glm::length(light.direction) < 1e-6f)
        throw InputError("light: the direction must not be zero");
    RendererState& state = *state_;
    // Stored as given: the frame constants and the shadow projection
    // normalise the direction themselves, and renormalising here could move
    // the last bit of an already unit vector (and with it pixels).
    // A changed light changes every lit radiance the temporal filters hold;
    // they see it through the version (FrameResources::lighting_version).
    if (!(state.scene.key_light == light)) ++state.frame.lighting_version;
    state.scene.key_light = light;
    state.frame.shadow = shadow_projection(state.scene, state.settings.shadow_map_size);
}

const FrameStatistics& Renderer::frame_statistics() const {
    RendererState& state = *state_;
    if (state.statistics) return *state.statistics;
    FrameStatistics statistics;
    statistics.exposure = state.settings.exposure == auto_length ? 1.0f : state.settings.exposure;
    if (state.last_camera) {
        // 2x1 RGBA32F (frame_statistics.comp): exposure, log-average, target,
        // pixels; near and far of layer 0 and of layer 1.
        std::array<float, 8> texels{};
        glGetTextureSubImage(state.frame.texture("frame_statistics"), 0, 0, 0, 0, 2, 1, 1, GL_RGBA,
                             GL_FLOAT, GLsizei(sizeof(texels)), texels.data());
        statistics.exposure = texels[0];
        statistics.log_average_luminance = texels[1];
        statistics.auto_exposure_target = texels[2];
        statistics.depth_ranges = {DepthRange{texels[4], texels[5]},
                                   DepthRange{texels[6], texels[7]}};
    }
    state.statistics = statistics;
    return *state.statistics;
}

float Renderer::exposure_in_use() const {
    return frame_statistics().exposure;
}

std::array<DepthRange, 2> Renderer::depth_ranges() const {
    return frame_statistics().depth_ranges;
}

const KeyLight& Renderer::key_light() const {
    return state_->scene.key_light;
}
FrameLayout Renderer::layout() const {
    return frame_layout(state_->settings);
}
const std::vector<PassTiming>& Renderer::last_timings() const {
    return state_->timer.timings();
}
bool Renderer::timing_uses_cpu_clock() const {
    return state_->timer.uses_cpu_clock();
}
bool Renderer::history_valid() const {
    return state_->frame.history_valid();
}
const std::vector<std::string>& Renderer::history_log() const {
    return state_->frame.history_log();
}
GLuint Renderer::output_texture() const {
    return state_->frame.display.get();
}

std::vector<std::uint8_t> Renderer::read_output_rgba8() const {
    return gl::read_rgba8(state_->frame.display.get(), 0, state_->settings.width,
                          state_->settings.height);
}

std::vector<std::string> Renderer::pass_output_names() const {
    std::vector<std::string> names;
    for (const auto& output : all_outputs(*state_)) names.push_back(output.name);
    return names;
}

FloatImage Renderer::read_pass_output(const std::string& name) const {
    const float near_plane = state_->last_camera ? state_->last_camera->near_plane : 0.05f;
    for (const auto& output : all_outputs(*state_)) {
        if (output.name == name) return deepgi::read_pass_output(output, near_plane);
    }
    throw InputError(fmt::format("no pass output named '{}'", name));
}

void Renderer::dump_pass_outputs(const fs::path& directory) const {
    // The whole set appears at once or not at all (a previous dump, holding
    // only .pfm files, is replaced whole); a failure names the file and errno.
    spiral::fileio::AtomicDirectory dump(directory, ".pfm");
    const float near_plane = state_->last_camera ? state_->last_camera->near_plane : 0.05f;
    for (const auto& output : all_outputs(*state_)) {
        const std::vector<std::uint8_t> bytes =
            encode_pfm(deepgi::read_pass_output(output, near_plane));
        dump.write_file(output.name + ".pfm", bytes.data(), bytes.size());
    }
    dump.commit();
}

}  // namespace deepgi
