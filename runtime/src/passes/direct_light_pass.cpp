#include "passes/passes.hpp"
#include "shader_shared.hpp"

namespace deepgi {

void draw_fullscreen_triangle(GLuint empty_vertex_array) {
    glBindVertexArray(empty_vertex_array);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

DirectLightPass create_direct_light_pass(const ShaderLoader& loader, int width, int height) {
    DirectLightPass pass;
    pass.width = width;
    pass.height = height;
    pass.program = loader.build_program(
        {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "direct_light.frag"}});
    pass.radiance = gl::create_texture_array(GL_R11F_G11F_B10F, width, height, DEEPGI_LAYER_COUNT);
    for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer) {
        pass.layer_framebuffers[layer] = gl::create_framebuffer();
        glNamedFramebufferTextureLayer(pass.layer_framebuffers[layer].get(), GL_COLOR_ATTACHMENT0,
                                       pass.radiance.get(), 0, layer);
        gl::check_framebuffer(pass.layer_framebuffers[layer], "direct light");
    }
    return pass;
}

void run_direct_light_pass(const DirectLightPass& pass, const GBufferTargets& gbuffer,
                           const ShadowPass& shadow, GLuint empty_vertex_array) {
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, pass.width, pass.height);
    glBindTextureUnit(DEEPGI_UNIT_GBUFFER_NORMAL, gbuffer.normal.get());
    glBindTextureUnit(DEEPGI_UNIT_GBUFFER_ALBEDO, gbuffer.albedo.get());
    glBindTextureUnit(DEEPGI_UNIT_GBUFFER_DEPTH, gbuffer.depth.get());
    glBindTextureUnit(DEEPGI_UNIT_SHADOW_MAP, shadow.depth.get());
    glUseProgram(pass.program.get());
    for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer) {
        glBindFramebuffer(GL_FRAMEBUFFER, pass.layer_framebuffers[layer].get());
        glProgramUniform1i(pass.program.get(), DEEPGI_UNIFORM_LAYER, layer);
        draw_fullscreen_triangle(empty_vertex_array);
    }
}

}  // namespace deepgi
