// Deep radiosity (design.md 3, steps 6 and 8): the gather of radiosity.frag
// for both G-buffer layers, writing E and confidence into a ping-pong history
// pair per layer (the previous slot feeds the next frame's bounce), and the
// bilateral blur of layer 0's result that the compose pass reads.
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>

namespace deepgi {

namespace {

std::string history_name(int layer) {
    return fmt::format("radiosity-layer{}", layer);
}

class RadiosityPass final : public Pass {
public:
    explicit RadiosityPass(const ShaderLoader& loader)
        : program_(build_fullscreen_program(loader, "radiosity.frag")) {}

    std::string_view name() const override { return "radiosity"; }

    void resize(FrameResources& frame) override {
        width_ = frame.layout.internal_width;
        height_ = frame.layout.internal_height;
        for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer) {
            HistoryPair& pair =
                frame.allocate_history(history_name(layer), GL_RGBA16F, width_, height_);
            for (int slot = 0; slot < 2; ++slot) {
                framebuffers_[layer][slot] = gl::create_framebuffer();
                glNamedFramebufferTexture(framebuffers_[layer][slot].get(), GL_COLOR_ATTACHMENT0,
                                          pair.slots[slot].get(), 0);
                gl::check_framebuffer(framebuffers_[layer][slot], "radiosity");
            }
        }
    }

    void run(FrameResources& frame) override {
        const RadiositySettings& settings = frame.settings->radiosity;
        const GLuint program = program_.get();
        glUseProgram(program);
        glProgramUniform4f(program, DEEPGI_UNIFORM_RADIOSITY_PARAMETERS, settings.radius,
                           settings.boost, settings.tap_clamp, settings.rho_prop);
        glProgramUniform1i(program, DEEPGI_UNIFORM_RADIOSITY_LAYERS, settings.layers);
        glBindTextureUnit(DEEPGI_UNIT_GBUFFER_NORMAL, frame.texture("gbuffer.normal"));
        glBindTextureUnit(DEEPGI_UNIT_GBUFFER_ALBEDO, frame.texture("gbuffer.albedo"));
        glBindTextureUnit(DEEPGI_UNIT_GBUFFER_EMISSIVE, frame.texture("gbuffer.emissive"));
        glBindTextureUnit(DEEPGI_UNIT_GBUFFER_DEPTH, frame.texture("gbuffer.depth"));
        glBindTextureUnit(DEEPGI_UNIT_DIRECT_LIGHT, frame.texture("direct_light.radiance"));
        glBindTextureUnit(DEEPGI_UNIT_RADIOSITY_PREVIOUS_LAYER0,
                          frame.history(history_name(0)).previous());
        glBindTextureUnit(DEEPGI_UNIT_RADIOSITY_PREVIOUS_LAYER1,
                          frame.history(history_name(1)).previous());
        for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer) {
            const HistoryPair& pair = frame.history(history_name(layer));
            begin_fullscreen(framebuffers_[layer][pair.written_slot].get(), width_, height_);
            glProgramUniform1i(program, DEEPGI_UNIFORM_LAYER, layer);
            draw_fullscreen_triangle(frame.empty_vertex_array);
            written_[layer] = pair.written();
            frame.publish(fmt::format("radiosity.irradiance.layer{}", layer), pair.written());
        }
    }

    std::vector<PassOutput> outputs(const FrameResources&) const override {
        std::vector<PassOutput> list;
        for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer) {
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
    gl::Program program_;
    gl::Framebuffer framebuffers_[DEEPGI_LAYER_COUNT][2];  // [layer][history slot]
    GLuint written_[DEEPGI_LAYER_COUNT] = {};              // this frame's E + confidence
    int width_ = 0;
    int height_ = 0;
};

// Smooths layer 0's E and confidence with the AO's bilateral blur.
class RadiosityBlurPass final : public Pass {
public:
    explicit RadiosityBlurPass(const ShaderLoader& loader) : blur_(create_bilateral_blur(loader)) {}

    std::string_view name() const override { return "radiosity_blur"; }

    void resize(FrameResources& frame) override {
        resize_bilateral_blur(blur_, frame.layout.internal_width, frame.layout.internal_height,
                              GL_RGBA16F);
        label_texture(blur_.horizontal, name(), "horizontal");
        label_texture(blur_.output, name(), "output");
    }

    void run(FrameResources& frame) override {
        run_bilateral_blur(blur_, frame.texture("radiosity.irradiance.layer0"),
                           frame.texture("depth_pyramid"), frame.texture("gbuffer.normal"),
                           frame.empty_vertex_array);
        frame.publish("radiosity.blurred", blur_.output.get());
    }

    std::vector<PassOutput> outputs(const FrameResources&) const override {
        return {{.name = "radiosity-blurred",
                 .texture = blur_.output.get(),
                 .width = blur_.width,
                 .height = blur_.height},
                {.name = "radiosity-blurred-confidence",
                 .texture = blur_.output.get(),
                 .width = blur_.width,
                 .height = blur_.height,
                 .channels = 1,
                 .decode = OutputDecode::alpha}};
    }

private:
    BilateralBlur blur_;
};

}  // namespace

std::unique_ptr<Pass> make_radiosity_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<RadiosityPass>(loader);
}

std::unique_ptr<Pass> make_radiosity_blur_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<RadiosityBlurPass>(loader);
}

}  // namespace deepgi
