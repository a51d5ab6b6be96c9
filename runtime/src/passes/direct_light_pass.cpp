// Lambertian key light with PCF shadows on both G-buffer layers (docs/design.md,
// section 5.4), one draw per layer into an RGBA16F array. It is the one-bounce
// gather's source, so its format decides a bias: R11F_G11F_B10F (6- and
// 5-bit mantissas) may truncate, and llvmpipe does, which made E about 1.5%
// too dark on ref-crease (docs/radiosity-studies.md, "Where the error against
// the visible truth comes from"); a 10-bit mantissa leaves under 0.1%.
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>

namespace deepgi {

namespace {

// Texture bindings of direct_light.frag (the shadow maps' are the ones it
// gives lighting.glsl).
constexpr GLuint normal_binding = 0;
constexpr GLuint albedo_binding = 1;
constexpr GLuint depth_binding = 4;
constexpr GLuint shadow_map_binding = 6;
constexpr GLuint shadow_cube_binding = 27;
constexpr GLint layer_location = 4;  // the G-buffer layer lit by this draw

class DirectLightPass final : public Pass {
public:
    explicit DirectLightPass(const ShaderLoader& loader)
        : program_(build_fullscreen_program(loader, "direct_light.frag")) {}

    std::string_view name() const override { return "direct_light"; }

    PassDeclaration declaration(const RenderSettings&) const override {
        return {.reads = {{normal_binding, "gbuffer.normal"},
                          {albedo_binding, "gbuffer.albedo"},
                          {depth_binding, "gbuffer.depth"},
                          {shadow_map_binding, "shadow.depth"},
                          {shadow_cube_binding, "shadow.cube"}},
                .writes = {"direct_light.radiance"}};
    }

    void resize(FrameResources& frame) override {
        width_ = frame.layout.internal_width;
        height_ = frame.layout.internal_height;
        radiance_ = gl::create_texture_array(GL_RGBA16F, width_, height_, DEEPGI_LAYER_COUNT);
        label_texture(radiance_, name(), "radiance");
        for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer) {
            layer_framebuffers_[layer] = gl::create_framebuffer();
            glNamedFramebufferTextureLayer(layer_framebuffers_[layer].get(), GL_COLOR_ATTACHMENT0,
                                           radiance_.get(), 0, layer);
            gl::check_framebuffer(layer_framebuffers_[layer], "direct light");
        }
    }

    void run(FrameResources& frame) override {
        glUseProgram(program_.get());
        for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer) {
            begin_fullscreen(layer_framebuffers_[layer].get(), width_, height_);
            glProgramUniform1i(program_.get(), layer_location, layer);
            draw_fullscreen_triangle(frame.empty_vertex_array);
        }
        frame.publish("direct_light.radiance", radiance_.get());
    }

    std::vector<PassOutput> outputs(const FrameResources&) const override {
        std::vector<PassOutput> list;
        for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer)
            list.push_back({.name = fmt::format("direct_light-radiance-layer{}", layer),
                            .texture = radiance_.get(),
                            .layer = layer,
                            .width = width_,
                            .height = height_});
        return list;
    }

private:
    gl::Program program_;
    gl::Texture radiance_;  // one layer per G-buffer layer
    gl::Framebuffer layer_framebuffers_[DEEPGI_LAYER_COUNT];
    int width_ = 0;
    int height_ = 0;
};

}  // namespace

std::unique_ptr<Pass> make_direct_light_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<DirectLightPass>(loader);
}

}  // namespace deepgi
