// Temporal filter of the mirror reflections (shaders/reflection_temporal.frag,
// docs/reflections.md "Temporal filter"): at a still camera, the running mean
// of the reflection pass's frames, whose march offsets follow the frame
// sequence; under motion, this frame's march alone. Runs when the reflection
// pass runs; compose reads its result.
#include "passes/passes.hpp"
#include "shader_shared.hpp"

namespace deepgi {

namespace {

// Texture bindings of reflection_temporal.frag.
constexpr GLuint normal_binding = 0;
constexpr GLuint motion_binding = 1;
constexpr GLuint depth_binding = 2;
constexpr GLuint raw_binding = 3;
constexpr GLuint history_binding = 4;
constexpr GLuint history_key_binding = 5;
constexpr GLint lighting_changed_location = 0;  // int uniform: 1 the frame the light changed

constexpr const char* radiance_history = "reflection-temporal";  // filtered radiance, weight
constexpr const char* key_history = "reflection-temporal-key";

class ReflectionTemporalPass final : public Pass {
public:
    ReflectionTemporalPass(const ShaderLoader& loader, const Scene& scene)
        : scene_(&scene), program_(build_fullscreen_program(loader, "reflection_temporal.frag")) {}

    std::string_view name() const override { return "reflection_temporal"; }

    bool enabled(const RenderSettings& settings) const override {
        return reflections_traced(*scene_, settings);
    }

    PassDeclaration declaration(const RenderSettings&) const override {
        return {.reads = {{normal_binding, "gbuffer.normal"},
                          {motion_binding, "gbuffer.motion"},
                          {depth_binding, "depth_pyramid"},
                          {raw_binding, "reflection.radiance"}},
                .writes = {"reflection.filtered"},
                // Whether it runs: reflections_traced() reads the mirror threshold.
                .value_reads = {"gbuffer.mirror_roughness"}};
    }

    void resize(FrameResources& frame) override {
        width_ = frame.layout.internal_width;
        height_ = frame.layout.internal_height;
        // 32-bit, as the AO and radiosity histories: a running mean of up to
        // DEEPGI_TEMPORAL_CAP frames would stop moving in float16.
        HistoryPair& radiance =
            frame.allocate_history(radiance_history, GL_RGBA32F, width_, height_);
        HistoryPair& key = frame.allocate_history(key_history, GL_RGBA16F, width_, height_);
        for (int slot = 0; slot < 2; ++slot) {
            gl::Framebuffer& framebuffer = framebuffers_[slot];
            framebuffer = gl::create_framebuffer();
            glNamedFramebufferTexture(framebuffer.get(), GL_COLOR_ATTACHMENT0,
                                      radiance.slots[slot].get(), 0);
            glNamedFramebufferTexture(framebuffer.get(), GL_COLOR_ATTACHMENT1,
                                      key.slots[slot].get(), 0);
            const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
            glNamedFramebufferDrawBuffers(framebuffer.get(), 2, buffers);
            gl::check_framebuffer(framebuffer, "reflection temporal");
        }
    }

    void run(FrameResources& frame) override {
        const HistoryPair& radiance = frame.history(radiance_history);
        glUseProgram(program_.get());
        glProgramUniform1i(program_.get(), lighting_changed_location,
                           frame.lighting_version != lighting_version_ ? 1 : 0);
        lighting_version_ = frame.lighting_version;
        glBindTextureUnit(history_binding, radiance.previous());
        glBindTextureUnit(history_key_binding, frame.history(key_history).previous());
        begin_fullscreen(framebuffers_[radiance.written_slot].get(), width_, height_);
        draw_fullscreen_triangle(frame.empty_vertex_array);
        written_ = radiance.written();
        frame.publish("reflection.filtered", written_);
    }

    std::vector<PassOutput> outputs(const FrameResources&) const override {
        return {{.name = "reflection-temporal",
                 .texture = written_,
                 .width = width_,
                 .height = height_,
                 .channels = 3}};
    }

private:
    const Scene* scene_;  // the renderer's own copy, which outlives its passes
    gl::Program program_;
    gl::Framebuffer framebuffers_[2];     // per history slot: radiance + key
    GLuint written_ = 0;                  // this frame's slot
    std::uint64_t lighting_version_ = 0;  // FrameResources::lighting_version at the last run
    int width_ = 0;
    int height_ = 0;
};

}  // namespace

std::unique_ptr<Pass> make_reflection_temporal_pass(const ShaderLoader& loader,
                                                    const Scene& scene) {
    return std::make_unique<ReflectionTemporalPass>(loader, scene);
}

}  // namespace deepgi
