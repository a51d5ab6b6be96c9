#include "passes/passes.hpp"
#include "shader_shared.hpp"

namespace deepgi {

DebugViewPass create_debug_view_pass(const ShaderLoader& loader) {
    DebugViewPass pass;
    pass.program = loader.build_program(
        {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "debug_view.frag"}});
    return pass;
}

void run_debug_view_pass(const DebugViewPass& pass, const GBufferTargets& gbuffer,
                         const DirectLightPass& direct, GLuint ao_raw, GLuint ao_blurred,
                         const TonemapPass& output, GLuint empty_vertex_array) {
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, output.width, output.height);
    glBindTextureUnit(DEEPGI_UNIT_GBUFFER_NORMAL, gbuffer.normal.get());
    glBindTextureUnit(DEEPGI_UNIT_GBUFFER_ALBEDO, gbuffer.albedo.get());
    glBindTextureUnit(DEEPGI_UNIT_GBUFFER_EMISSIVE, gbuffer.emissive.get());
    glBindTextureUnit(DEEPGI_UNIT_GBUFFER_MOTION, gbuffer.motion.get());
    glBindTextureUnit(DEEPGI_UNIT_GBUFFER_DEPTH, gbuffer.depth.get());
    glBindTextureUnit(DEEPGI_UNIT_DIRECT_LIGHT, direct.radiance.get());
    glBindTextureUnit(DEEPGI_UNIT_AO_RAW, ao_raw);
    glBindTextureUnit(DEEPGI_UNIT_AO, ao_blurred);
    glBindFramebuffer(GL_FRAMEBUFFER, output.framebuffer.get());
    glUseProgram(pass.program.get());
    draw_fullscreen_triangle(empty_vertex_array);
}

}  // namespace deepgi
