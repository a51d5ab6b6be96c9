// Separable bilateral blur (design.md 3, step 5): a horizontal draw into an
// intermediate texture, then a vertical draw into the output. The kernel is
// the generated blur_kernel.glsl the shader loader finds.
#include "deepgi/errors.hpp"
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <cmath>

namespace deepgi {

namespace {

void check_parameters(const BilateralBlurParameters& parameters) {
    auto positive = [](float value) { return std::isfinite(value) && value > 0.0f; };
    if (!positive(parameters.depth_tolerance) || !positive(parameters.normal_power) ||
        !positive(parameters.plane_tolerance)) {
        throw InputError("bilateral blur tolerances and normal power must be finite and > 0");
    }
}

// Smooths the raw deep SAO visibility.
class AoBlurPass final : public Pass {
public:
    explicit AoBlurPass(const ShaderLoader& loader) : blur_(create_bilateral_blur(loader)) {}

    std::string_view name() const override { return "ao_blur"; }

    void resize(FrameResources& frame) override {
        resize_bilateral_blur(blur_, frame.layout.internal_width, frame.layout.internal_height,
                              GL_R16F);
        label_texture(blur_.horizontal, name(), "horizontal");
        label_texture(blur_.output, name(), "output");
    }

    void run(FrameResources& frame) override {
        run_bilateral_blur(blur_, frame.texture("ao.temporal"), frame.texture("depth_pyramid"),
                           frame.texture("gbuffer.normal"), frame.empty_vertex_array);
        frame.publish("ao.blurred", blur_.output.get());
    }

    std::vector<PassOutput> outputs(const FrameResources&) const override {
        return {{.name = "ao-blurred",
                 .texture = blur_.output.get(),
                 .width = blur_.width,
                 .height = blur_.height,
                 .channels = 1}};
    }

private:
    BilateralBlur blur_;
};

}  // namespace

BilateralBlur create_bilateral_blur(const ShaderLoader& loader,
                                    const BilateralBlurParameters& parameters) {
    check_parameters(parameters);
    BilateralBlur blur;
    blur.parameters = parameters;
    blur.program = build_fullscreen_program(loader, "bilateral_blur.frag");
    return blur;
}

void resize_bilateral_blur(BilateralBlur& blur, int width, int height, GLenum internal_format) {
    blur.width = width;
    blur.height = height;
    blur.horizontal = gl::create_texture_2d(internal_format, width, height);
    blur.output = gl::create_texture_2d(internal_format, width, height);
    blur.horizontal_framebuffer = framebuffer_for(blur.horizontal, "bilateral blur");
    blur.output_framebuffer = framebuffer_for(blur.output, "bilateral blur");
}

void run_bilateral_blur(const BilateralBlur& blur, GLuint source, GLuint depth_pyramid,
                        GLuint gbuffer_normal, GLuint empty_vertex_array) {
    const GLuint program = blur.program.get();
    glUseProgram(program);
    glProgramUniform4f(program, DEEPGI_UNIFORM_BLUR_PARAMETERS, blur.parameters.depth_tolerance,
                       blur.parameters.normal_power, blur.parameters.plane_tolerance, 0.0f);
    glBindTextureUnit(DEEPGI_UNIT_DEPTH_PYRAMID, depth_pyramid);
    glBindTextureUnit(DEEPGI_UNIT_GBUFFER_NORMAL, gbuffer_normal);

    glBindTextureUnit(DEEPGI_UNIT_BLUR_SOURCE, source);
    glProgramUniform2i(program, DEEPGI_UNIFORM_BLUR_DIRECTION, 1, 0);
    begin_fullscreen(blur.horizontal_framebuffer.get(), blur.width, blur.height);
    draw_fullscreen_triangle(empty_vertex_array);

    glBindTextureUnit(DEEPGI_UNIT_BLUR_SOURCE, blur.horizontal.get());
    glProgramUniform2i(program, DEEPGI_UNIFORM_BLUR_DIRECTION, 0, 1);
    begin_fullscreen(blur.output_framebuffer.get(), blur.width, blur.height);
    draw_fullscreen_triangle(empty_vertex_array);
}

std::unique_ptr<Pass> make_ao_blur_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<AoBlurPass>(loader);
}

}  // namespace deepgi
