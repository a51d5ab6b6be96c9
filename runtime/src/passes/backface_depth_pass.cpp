// Where the solid behind each G-buffer layer ends (backface_depth.frag,
// docs/deep-sao.md "The march"): per layer, the nearest back face at or
// behind the layer's stored depth. The AO march and the mirror reflections
// read it, and so does the radiosity gather's visibility test, so the pass
// runs only for them, and only for the layers they use.
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>

namespace deepgi {

namespace {

// Texture bindings of backface_depth.frag (the material's base colour is
// alpha_mask.glsl's, through draw_scene_depth).
constexpr GLuint depth_binding = 4;
constexpr GLuint base_colour_binding = 9;
// The G-buffer layer the back faces must lie behind (uniform location).
constexpr GLint layer_location = 39;

class BackfaceDepthPass final : public Pass {
public:
    BackfaceDepthPass(const ShaderLoader& loader, const Scene& scene)
        : scene_(&scene),
          program_(loader.build_program({{GL_VERTEX_SHADER, "backface_depth.vert"},
                                         {GL_FRAGMENT_SHADER, "backface_depth.frag"}})),
          masked_program_(loader.build_program({{GL_VERTEX_SHADER, "backface_depth.vert"},
                                                {GL_FRAGMENT_SHADER, "backface_depth.frag"}},
                                               "#define ALPHA_MASK 1\n")) {}

    std::string_view name() const override { return "backface_depth"; }

    PassDeclaration declaration(const RenderSettings& settings) const override {
        // How many layers is its readers' to say: SAO's and the reflections'
        // layer counts, read from the settings where the frame asks whether
        // the pass runs (before any value is known), so declared here.
        // Whether reflections are traced depends on which materials are mirrors.
        PassDeclaration declaration = {.reads = {{depth_binding, "gbuffer.depth"}},
                                       .writes = {"backface.depth"},
                                       .value_reads = {"gbuffer.mirror_roughness"}};
        if (ao_method_reads_back_faces(settings.ao.method))
            declaration.value_reads.push_back("sao.layers");
        if (reflections_traced(*scene_, settings))
            declaration.value_reads.push_back("reflection.layers");
        // Whether the radiosity gather tests visibility decides whether it
        // reads back faces at all, so these are read whatever their values.
        declaration.value_reads.push_back("radiosity.visibility_steps");
        declaration.value_reads.push_back("radiosity.layers");
        return declaration;
    }

    bool enabled(const RenderSettings& settings) const override { return layers(settings) > 0; }

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
        for (int layer = 0; layer < layers(*frame.settings); ++layer) {
            const GLuint framebuffer = framebuffers_[std::size_t(layer)].get();
            const float nothing_hit = 0.0f;  // reversed Z: 0 is infinitely far
            glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &nothing_hit);
            glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
            for (GLuint program : {program_.get(), masked_program_.get()})
                glProgramUniform1i(program, layer_location, layer);
            draw_scene_depth(*frame.scene_gpu, program_.get(), masked_program_.get(),
                             base_colour_binding);
        }
        glCullFace(GL_BACK);
        frame.publish("backface.depth", depth_.get());
    }

    std::vector<PassOutput> outputs(const FrameResources& frame) const override {
        std::vector<PassOutput> list;
        for (int layer = 0; layer < layers(*frame.settings); ++layer)
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
    // The layers whose solids are read: the AO estimator's when it reads back
    // faces (the march, the thick spiral; the SAO pass runs, and binds this,
    // whether or not compose uses AO), the reflections' and the radiosity
    // gather's when it tests visibility.
    int layers(const RenderSettings& settings) const {
        const int for_ao = ao_method_reads_back_faces(settings.ao.method) ? settings.ao.layers : 0;
        const int for_reflections =
            reflections_traced(*scene_, settings) ? settings.reflection.layers : 0;
        const int for_radiosity =
            settings.radiosity.visibility_steps > 0 ? settings.radiosity.layers : 0;
        return std::max({for_ao, for_reflections, for_radiosity});
    }

    const Scene* scene_;  // the renderer's own copy, which outlives its passes
    gl::Program program_;
    gl::Program masked_program_;  // ALPHA_MASK: for alpha-masked batches
    gl::Texture depth_;           // DEPTH_COMPONENT32F array, near / z (reversed, infinite)
    std::array<gl::Framebuffer, DEEPGI_LAYER_COUNT> framebuffers_;
    int width_ = 0;
    int height_ = 0;
};

}  // namespace

std::unique_ptr<Pass> make_backface_depth_pass(const ShaderLoader& loader, const Scene& scene) {
    return std::make_unique<BackfaceDepthPass>(loader, scene);
}

}  // namespace deepgi
