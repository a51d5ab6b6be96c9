// Where the solid behind each G-buffer layer ends (backface_depth.frag,
// docs/deep-sao.md "The march"): per layer, the nearest back face at or
// behind the layer's stored depth. Only the march reads it, so the pass runs
// only with that method, and only for the layers the AO gathers.
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>

#include <array>

namespace deepgi {

namespace {

class BackfaceDepthPass final : public Pass {
public:
    explicit BackfaceDepthPass(const ShaderLoader& loader)
        : program_(loader.build_program({{GL_VERTEX_SHADER, "backface_depth.vert"},
                                         {GL_FRAGMENT_SHADER, "backface_depth.frag"}})),
          masked_program_(loader.build_program({{GL_VERTEX_SHADER, "backface_depth.vert"},
                                                {GL_FRAGMENT_SHADER, "backface_depth.frag"}},
                                               "#define ALPHA_MASK 1\n")) {}

    std::string_view name() const override { return "backface_depth"; }

    PassDeclaration declaration(const RenderSettings&) const override {
        return {.reads = {{DEEPGI_UNIT_GBUFFER_DEPTH, "gbuffer.depth"}},
                .writes = {"backface.depth"}};
    }

    bool enabled(const RenderSettings& settings) const override {
        // The SAO pass runs (and binds this) whether or not compose uses AO.
        return ao_method_reads_back_faces(settings.ao.method);
    }

    void resize(FrameResources& frame) override {
        width_ = frame.layout.internal_width;
        height_ = frame.layout.internal_height;
        depth_ =
            gl::create_texture_array(GL_DEPTH_COMPONENT32F, width_, height_, DEEPGI_LAYER_COUNT);
        label_texture(depth_, name(), "depth");
        for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer) {
            gl::Framebuffer& framebuffer = framebuffers_[std::size_t(layer)];
            framebuffer = gl::create_framebuffer();
            glNamedFramebufferTextureLayer(framebuffer.get(), GL_DEPTH_ATTACHMENT, depth_.get(), 0,
                                           layer);
            glNamedFramebufferDrawBuffer(framebuffer.get(), GL_NONE);
            gl::check_framebuffer(framebuffer, "backface depth");
        }
    }

    void run(FrameResources& frame) override {
        glViewport(0, 0, width_, height_);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);
        glDepthMask(GL_TRUE);
        glEnable(GL_CULL_FACE);
        glCullFace(GL_FRONT);
        for (int layer = 0; layer < frame.settings->ao.layers; ++layer) {
            const GLuint framebuffer = framebuffers_[std::size_t(layer)].get();
            const float nothing_hit = 0.0f;  // reversed Z: 0 is infinitely far
            glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &nothing_hit);
            glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
            for (GLuint program : {program_.get(), masked_program_.get()})
                glProgramUniform1i(program, DEEPGI_UNIFORM_BACKFACE_LAYER, layer);
            draw_scene_depth(*frame.scene_gpu, program_.get(), masked_program_.get());
        }
        glCullFace(GL_BACK);
        frame.publish("backface.depth", depth_.get());
    }

    std::vector<PassOutput> outputs(const FrameResources& frame) const override {
        std::vector<PassOutput> list;
        for (int layer = 0; layer < frame.settings->ao.layers; ++layer)
            list.push_back({.name = fmt::format("backface-depth-layer{}", layer),
                            .texture = depth_.get(),
                            .layer = layer,
                            .width = width_,
                            .height = height_,
                            .channels = 1,
                            .decode = OutputDecode::depth_to_metres});
        return list;
    }

private:
    gl::Program program_;
    gl::Program masked_program_;  // ALPHA_MASK: for alpha-masked batches
    gl::Texture depth_;           // DEPTH_COMPONENT32F array, near / z (reversed, infinite)
    std::array<gl::Framebuffer, DEEPGI_LAYER_COUNT> framebuffers_;
    int width_ = 0;
    int height_ = 0;
};

}  // namespace

std::unique_ptr<Pass> make_backface_depth_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<BackfaceDepthPass>(loader);
}

}  // namespace deepgi
