#include "passes/passes.hpp"
#include "shader_shared.hpp"

namespace deepgi {

ComposePass create_compose_pass(const ShaderLoader& loader, int width, int height) {
    ComposePass pass;
    pass.width = width;
    pass.height = height;
    pass.program = loader.build_program(
        {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "compose.frag"}});
    pass.radiance = gl::create_texture_2d(GL_R11F_G11F_B10F, width, height);
    pass.framebuffer = gl::create_framebuffer();
    glNamedFramebufferTexture(pass.framebuffer.get(), GL_COLOR_ATTACHMENT0, pass.radiance.get(), 0);
    gl::check_framebuffer(pass.framebuffer, "compose");
    return pass;
}

void run_compose_pass(const ComposePass& pass, const GBufferTargets& gbuffer,
                      const DirectLightPass& direct, GLuint ambient_visibility,
                      GLuint empty_vertex_array) {
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, pass.width, pass.height);
    glBindTextureUnit(DEEPGI_UNIT_DIRECT_LIGHT, direct.radiance.get());
    glBindTextureUnit(DEEPGI_UNIT_GBUFFER_ALBEDO, gbuffer.albedo.get());
    glBindTextureUnit(DEEPGI_UNIT_GBUFFER_EMISSIVE, gbuffer.emissive.get());
    glBindTextureUnit(DEEPGI_UNIT_GBUFFER_DEPTH, gbuffer.depth.get());
    glBindTextureUnit(DEEPGI_UNIT_AO, ambient_visibility);
    glBindFramebuffer(GL_FRAMEBUFFER, pass.framebuffer.get());
    glUseProgram(pass.program.get());
    draw_fullscreen_triangle(empty_vertex_array);
}

}  // namespace deepgi
