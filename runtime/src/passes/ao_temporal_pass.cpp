// Temporal filter of the ambient visibility (shaders/ao_temporal.frag): SAO's
// raw result, whose taps turn by a new angle each frame, accumulated with
// history found through the G-buffer's motion vectors.
// The AO blur reads its result.
#include "passes/passes.hpp"
#include "shader_shared.hpp"

namespace deepgi {

namespace {

// Texture bindings of ao_temporal.frag.
constexpr GLuint normal_binding = 0;
constexpr GLuint motion_binding = 3;
constexpr GLuint depth_binding = 10;
constexpr GLuint raw_binding = 13;
constexpr GLuint history_binding = 11;
constexpr GLuint history_key_binding = 19;
constexpr GLint alpha_location = 29;  // uniform: the temporal blend weight

constexpr const char* visibility_history = "ao-temporal";  // filtered visibility
constexpr const char* key_history = "ao-temporal-key";

class AoTemporalPass final : public Pass {
public:
    explicit AoTemporalPass(const ShaderLoader& loader)
        : program_(build_fullscreen_program(loader, "ao_temporal.frag")) {}

    std::string_view name() const override { return "ao_temporal"; }

    PassDeclaration declaration(const RenderSettings&) const override {
        return {.reads = {{normal_binding, "gbuffer.normal"},
                          {motion_binding, "gbuffer.motion"},
                          {depth_binding, "depth_pyramid"},
                          {raw_binding, "ao.raw"}},
                .writes = {"ao.temporal"}};
    }

    void resize(FrameResources& frame) override {
        width_ = frame.layout.internal_width;
        height_ = frame.layout.internal_height;
        // Allocated together, so both pairs write the same slot each frame.
        // Float, not UNORM: the solid-angle visibility is signed (sao.frag).
        // 32-bit: a running mean of up to DEEPGI_TEMPORAL_CAP frames moves by
        // less than half a float16 step near 1, and would stop moving.
        HistoryPair& visibility =
            frame.allocate_history(visibility_history, GL_R32F, width_, height_);
        HistoryPair& key = frame.allocate_history(key_history, GL_RGBA16F, width_, height_);
        for (int slot = 0; slot < 2; ++slot) {
            gl::Framebuffer& framebuffer = framebuffers_[slot];
            framebuffer = gl::create_framebuffer();
            glNamedFramebufferTexture(framebuffer.get(), GL_COLOR_ATTACHMENT0,
                                      visibility.slots[slot].get(), 0);
            glNamedFramebufferTexture(framebuffer.get(), GL_COLOR_ATTACHMENT1,
                                      key.slots[slot].get(), 0);
            const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
            glNamedFramebufferDrawBuffers(framebuffer.get(), 2, buffers);
            gl::check_framebuffer(framebuffer, "ao temporal");
        }
    }

    void run(FrameResources& frame) override {
        const GLuint program = program_.get();
        const HistoryPair& visibility = frame.history(visibility_history);
        glUseProgram(program);
        glProgramUniform1f(program, alpha_location, frame.settings->ao.alpha);
        glBindTextureUnit(history_binding, visibility.previous());
        glBindTextureUnit(history_key_binding, frame.history(key_history).previous());
        begin_fullscreen(framebuffers_[visibility.written_slot].get(), width_, height_);
        draw_fullscreen_triangle(frame.empty_vertex_array);
        written_ = visibility.written();
        frame.publish("ao.temporal", written_);
    }

    std::vector<PassOutput> outputs(const FrameResources&) const override {
        return {{.name = "ao-temporal",
                 .texture = written_,
                 .width = width_,
                 .height = height_,
                 .channels = 1}};
    }

private:
    gl::Program program_;
    gl::Framebuffer framebuffers_[2];  // per history slot: visibility + key
    GLuint written_ = 0;               // this frame's slot
    int width_ = 0;
    int height_ = 0;
};

}  // namespace

std::unique_ptr<Pass> make_ao_temporal_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<AoTemporalPass>(loader);
}

}  // namespace deepgi
