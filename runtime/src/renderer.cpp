// The public Renderer (deepgi/renderer.hpp) around a RendererState: building
// it, settings and light changes (what each costs the passes), and reading
// results back. The frame itself runs in frame.cpp.
#include "deepgi/errors.hpp"
#include "deepgi/image_io.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/settings.hpp"
#include "gl/readback.hpp"
#include "passes/passes.hpp"
#include "renderer_state.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>
#include <spiral/fileio.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace deepgi {

namespace fs = std::filesystem;
using shader_shared::FrameConstants;

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
