#include "passes/passes.hpp"
#include "shader_shared.hpp"

namespace deepgi {

TonemapPass create_tonemap_pass(const ShaderLoader& loader, int viewport_width,
                                int viewport_height) {
    TonemapPass pass;
    pass.width = viewport_width;
    pass.height = viewport_height;
    pass.program = loader.build_program(
        {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "tonemap.frag"}});
    pass.colour = gl::create_texture_2d(GL_RGBA8, viewport_width, viewport_height);
    pass.framebuffer = gl::create_framebuffer();
    glNamedFramebufferTexture(pass.framebuffer.get(), GL_COLOR_ATTACHMENT0, pass.colour.get(), 0);
    gl::check_framebuffer(pass.framebuffer, "tonemap");
    return pass;
}

void run_tonemap_pass(const TonemapPass& pass, const ComposePass& compose,
                      GLuint empty_vertex_array) {
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, pass.width, pass.height);
    glBindTextureUnit(DEEPGI_UNIT_COMPOSE, compose.radiance.get());
    glBindFramebuffer(GL_FRAMEBUFFER, pass.framebuffer.get());
    glUseProgram(pass.program.get());
    draw_fullscreen_triangle(empty_vertex_array);
}

}  // namespace deepgi
