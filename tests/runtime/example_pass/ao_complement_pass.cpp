// An example pass, compiled into the pass interface test only: it shows what
// a new pass of runtime/src/passes/ takes (docs/architecture.md, "How to add
// a pass"). It reads one declared input, the blurred ambient visibility, and
// writes its complement (ao_complement.frag) to a texture of its own, which
// it publishes and lists for the dump.
#include "passes/passes.hpp"

namespace deepgi {

namespace {

// Texture binding of ao_complement.frag.
constexpr GLuint visibility_binding = 0;

class AoComplementPass final : public Pass {
public:
    explicit AoComplementPass(const ShaderLoader& loader)
        : program_(build_fullscreen_program(loader, "ao_complement.frag")) {}

    std::string_view name() const override { return "ao_complement"; }

    PassDeclaration declaration(const RenderSettings&) const override {
        return {.reads = {{visibility_binding, "ao.blurred"}}, .writes = {"ao_complement"}};
    }

    void resize(FrameResources& frame) override {
        width_ = frame.layout.internal_width;
        height_ = frame.layout.internal_height;
        occlusion_ = gl::create_texture_2d(GL_R16F, width_, height_);
        label_texture(occlusion_, name(), "occlusion");
        framebuffer_ = framebuffer_for(occlusion_, "ao complement");
    }

    void run(FrameResources& frame) override {
        // The frame has bound "ao.blurred" at visibility_binding.
        begin_fullscreen(framebuffer_.get(), width_, height_);
        glUseProgram(program_.get());
        draw_fullscreen_triangle(frame.empty_vertex_array);
        frame.publish("ao_complement", occlusion_.get());
    }

    std::vector<PassOutput> outputs(const FrameResources&) const override {
        return {{.name = "ao_complement-occlusion",
                 .texture = occlusion_.get(),
                 .width = width_,
                 .height = height_,
                 .channels = 1}};
    }

private:
    gl::Program program_;
    gl::Texture occlusion_;
    gl::Framebuffer framebuffer_;
    int width_ = 0;
    int height_ = 0;
};

}  // namespace

std::unique_ptr<Pass> make_ao_complement_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<AoComplementPass>(loader);
}

}  // namespace deepgi
