// Deep radiosity (docs/design.md, section 5.9): the gather of radiosity.frag
// for both G-buffer layers into raw E + confidence (reading what the prepare
// pass built), the temporal filter of radiosity_temporal.frag into ping-pong
// history pairs per layer (whose previous slot also feeds the next frame's
// bounce through the prepare pass), and the bilateral blur of layer 0's
// filtered result that the compose pass reads.
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>
#include <glm/glm.hpp>

#include <algorithm>

namespace deepgi {

namespace {

// Texture bindings of radiosity.frag (the gather) and radiosity_temporal.frag
// (the temporal filter), which share the G-buffer's and the pyramid's.
constexpr GLuint normal_binding = 0;
constexpr GLuint motion_binding = 3;
constexpr GLuint depth_binding = 10;
constexpr GLuint raw_binding = 17;
constexpr GLuint history_binding = 15;
constexpr GLuint history_key_binding = 19;
constexpr GLuint radiance_binding = 21;
constexpr GLuint prepared_normal_binding = 22;
// radiosity_visibility.glsl: where each stored surface's solid ends.
constexpr GLuint backface_binding = 29;
// Uniform locations: the layer (both shaders), the temporal blend weight.
constexpr GLint layer_location = 4;
constexpr GLint alpha_location = 29;
constexpr GLint lighting_changed_location = 30;  // int uniform: 1 the frame the light changed

std::string history_name(int layer) {
    return fmt::format("radiosity-layer{}", layer);
}
std::string key_name(int layer) {
    return fmt::format("radiosity-key-layer{}", layer);
}

class RadiosityPass final : public Pass {
public:
    explicit RadiosityPass(const ShaderLoader& loader)
        : gather_(build_fullscreen_program(loader, "radiosity.frag")),
          // The visibility test is compiled only into its own program: on
          // llvmpipe its code in the default program, never run, made the
          // default gather about twice as slow.
          gather_visible_(build_fullscreen_program(loader, "radiosity.frag",
                                                   "#define RADIOSITY_VISIBILITY 1\n")),
          temporal_(build_fullscreen_program(loader, "radiosity_temporal.frag")) {}

    std::string_view name() const override { return "radiosity"; }

    PassDeclaration declaration(const RenderSettings& settings) const override {
        const RadiositySettings& radiosity = settings.radiosity;
        PassDeclaration declaration = {
            .reads = {{depth_binding, "depth_pyramid"},
                      {radiance_binding, "radiosity_prepare.radiance"},
                      {prepared_normal_binding, "radiosity_prepare.normal"},
                      {normal_binding, "gbuffer.normal"},
                      {motion_binding, "gbuffer.motion"}},
            .writes = {"radiosity.raw.layer0", "radiosity.raw.layer1",
                       "radiosity.irradiance.layer0", "radiosity.irradiance.layer1"},
            // The pyramid's MIP selection, as SAO uses it.
            .value_reads = {"depth_pyramid.q"},
            // How many layers backface_depth renders for the visibility test.
            .value_writes = {{"radiosity.radius", radiosity.radius},
                             {"radiosity.layers", float(radiosity.layers)},
                             {"radiosity.visibility_steps", float(radiosity.visibility_steps)}}};
        if (radiosity.visibility_steps > 0) {
            // The visibility test treats stored surfaces as solids as the AO
            // march does: to their back faces, or the AO's thickness behind
            // an open mesh.
            declaration.reads.push_back({backface_binding, "backface.depth"});
            declaration.value_reads.push_back("sao.thickness");
        }
        return declaration;
    }

    SettingsChange settings_change(const RenderSettings& before,
                                   const RenderSettings& after) const override {
        SettingsChange change = Pass::settings_change(before, after);
        // The estimators' E and confidence mean different things
        // (docs/radiosity.md): history of one would take cycles to fade from
        // the other.
        if (change.drop_history.empty() && after.radiosity.method != before.radiosity.method)
            change.drop_history =
                fmt::format("radiosity method changed to {}", to_string(after.radiosity.method));
        return change;
    }

    void resize(FrameResources& frame) override {
        width_ = frame.layout.internal_width;
        height_ = frame.layout.internal_height;
        for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer) {
            raw_[layer] = gl::create_texture_2d(GL_RGBA16F, width_, height_);
            label_texture(raw_[layer], name(), fmt::format("raw layer {}", layer));
            raw_framebuffers_[layer] = framebuffer_for(raw_[layer], "radiosity raw");
            // Allocated together, so both pairs write the same slot each frame.
            // RGBA32F: a running mean of up to DEEPGI_TEMPORAL_CAP frames moves
            // by (raw - mean) / 256 per frame, under one float16 step.
            HistoryPair& irradiance =
                frame.allocate_history(history_name(layer), GL_RGBA32F, width_, height_);
            HistoryPair& key = frame.allocate_history(key_name(layer), GL_RGBA16F, width_, height_);
            for (int slot = 0; slot < 2; ++slot) {
                gl::Framebuffer& framebuffer = framebuffers_[layer][slot];
                framebuffer = gl::create_framebuffer();
                glNamedFramebufferTexture(framebuffer.get(), GL_COLOR_ATTACHMENT0,
                                          irradiance.slots[slot].get(), 0);
                glNamedFramebufferTexture(framebuffer.get(), GL_COLOR_ATTACHMENT1,
                                          key.slots[slot].get(), 0);
                const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
                glNamedFramebufferDrawBuffers(framebuffer.get(), 2, buffers);
                gl::check_framebuffer(framebuffer, "radiosity temporal");
            }
        }
    }

    void run(FrameResources& frame) override {
        const RadiositySettings& settings = frame.settings->radiosity;
        const GLuint gather = settings.visibility_steps > 0 ? gather_visible_.get() : gather_.get();
        glUseProgram(gather);
        // The prepare pass builds as many levels as the depth pyramid.
        parameters_.bind(
            {.radius = settings.radius,
             .tap_clamp = settings.tap_clamp,
             .q = frame.value("depth_pyramid.q"),
             // Its own cap, within the levels the pyramid (and so the
             // prepare pass) built.
             .max_mip = std::min(settings.max_mip_level, frame.integer("depth_pyramid.max_level")),
             .layers = settings.layers,
             .method = static_cast<int>(settings.method),
             .visibility_steps = settings.visibility_steps,
             .visibility_thickness =
                 settings.visibility_steps > 0 ? frame.value("sao.thickness") : 0.0f});
        for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer) {
            begin_fullscreen(raw_framebuffers_[layer].get(), width_, height_);
            glProgramUniform1i(gather, layer_location, layer);
            draw_fullscreen_triangle(frame.empty_vertex_array);
        }

        const GLuint temporal = temporal_.get();
        glUseProgram(temporal);
        glProgramUniform1f(temporal, alpha_location, settings.alpha);
        glProgramUniform1i(temporal, lighting_changed_location,
                           frame.lighting_version != lighting_version_ ? 1 : 0);
        lighting_version_ = frame.lighting_version;
        for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer) {
            const HistoryPair& irradiance = frame.history(history_name(layer));
            glBindTextureUnit(raw_binding, raw_[layer].get());
            glBindTextureUnit(history_binding, irradiance.previous());
            glBindTextureUnit(history_key_binding, frame.history(key_name(layer)).previous());
            begin_fullscreen(framebuffers_[layer][irradiance.written_slot].get(), width_, height_);
            glProgramUniform1i(temporal, layer_location, layer);
            draw_fullscreen_triangle(frame.empty_vertex_array);
            written_[layer] = irradiance.written();
            frame.publish(fmt::format("radiosity.raw.layer{}", layer), raw_[layer].get());
            frame.publish(fmt::format("radiosity.irradiance.layer{}", layer), irradiance.written());
        }
    }

    std::vector<PassOutput> outputs(const FrameResources&) const override {
        std::vector<PassOutput> list;
        for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer) {
            list.push_back({.name = fmt::format("radiosity-raw-layer{}", layer),
                            .texture = raw_[layer].get(),
                            .width = width_,
                            .height = height_});
            list.push_back({.name = fmt::format("radiosity-irradiance-layer{}", layer),
                            .texture = written_[layer],
                            .width = width_,
                            .height = height_});
            list.push_back({.name = fmt::format("radiosity-confidence-layer{}", layer),
                            .texture = written_[layer],
                            .width = width_,
                            .height = height_,
                            .channels = 1,
                            .decode = OutputDecode::alpha});
        }
        return list;
    }

private:
    std::uint64_t lighting_version_ = 0;  // FrameResources::lighting_version at the last run
    gl::Program gather_;
    gl::Program gather_visible_;  // the same with the visibility test
    ParameterBlock<shader_shared::RadiosityGatherParameters> parameters_;
    gl::Program temporal_;
    gl::Texture raw_[DEEPGI_LAYER_COUNT];  // this frame's gather, before the temporal filter
    gl::Framebuffer raw_framebuffers_[DEEPGI_LAYER_COUNT];
    gl::Framebuffer framebuffers_[DEEPGI_LAYER_COUNT][2];  // [layer][slot]: E, key
    GLuint written_[DEEPGI_LAYER_COUNT] = {};              // this frame's filtered E + confidence
    int width_ = 0;
    int height_ = 0;
};

}  // namespace

std::unique_ptr<Pass> make_radiosity_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<RadiosityPass>(loader);
}

}  // namespace deepgi
