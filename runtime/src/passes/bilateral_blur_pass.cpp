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

void attach(gl::Framebuffer& framebuffer, const gl::Texture& texture) {
    framebuffer = gl::create_framebuffer();
    glNamedFramebufferTexture(framebuffer.get(), GL_COLOR_ATTACHMENT0, texture.get(), 0);
    gl::check_framebuffer(framebuffer, "bilateral blur");
}

}  // namespace

BilateralBlurPass create_bilateral_blur_pass(const ShaderLoader& loader, int width, int height,
                                             GLenum internal_format,
                                             const BilateralBlurParameters& parameters) {
    check_parameters(parameters);
    BilateralBlurPass pass;
    pass.width = width;
    pass.height = height;
    pass.parameters = parameters;
    pass.program = loader.build_program(
        {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "bilateral_blur.frag"}});
    pass.horizontal = gl::create_texture_2d(internal_format, width, height);
    pass.output = gl::create_texture_2d(internal_format, width, height);
    attach(pass.horizontal_framebuffer, pass.horizontal);
    attach(pass.output_framebuffer, pass.output);
    return pass;
}

void run_bilateral_blur_pass(const BilateralBlurPass& pass, GLuint source, GLuint depth_pyramid,
                             GLuint gbuffer_normal, GLuint empty_vertex_array) {
    const GLuint program = pass.program.get();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, pass.width, pass.height);
    glUseProgram(program);
    glProgramUniform4f(program, DEEPGI_UNIFORM_BLUR_PARAMETERS, pass.parameters.depth_tolerance,
                       pass.parameters.normal_power, pass.parameters.plane_tolerance, 0.0f);
    glBindTextureUnit(DEEPGI_UNIT_DEPTH_PYRAMID, depth_pyramid);
    glBindTextureUnit(DEEPGI_UNIT_GBUFFER_NORMAL, gbuffer_normal);

    glBindTextureUnit(DEEPGI_UNIT_BLUR_SOURCE, source);
    glProgramUniform2i(program, DEEPGI_UNIFORM_BLUR_DIRECTION, 1, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, pass.horizontal_framebuffer.get());
    draw_fullscreen_triangle(empty_vertex_array);

    glBindTextureUnit(DEEPGI_UNIT_BLUR_SOURCE, pass.horizontal.get());
    glProgramUniform2i(program, DEEPGI_UNIFORM_BLUR_DIRECTION, 0, 1);
    glBindFramebuffer(GL_FRAMEBUFFER, pass.output_framebuffer.get());
    draw_fullscreen_triangle(empty_vertex_array);
}

}  // namespace deepgi
