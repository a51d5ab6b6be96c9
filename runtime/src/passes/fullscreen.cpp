// Helpers every screen-space pass shares.
#include "frame_resources.hpp"
#include "pass.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>

namespace deepgi {

gl::Program build_fullscreen_program(const ShaderLoader& loader, const std::string& fragment,
                                     const std::string& defines) {
    return loader.build_program(
        {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, fragment}}, defines);
}

void begin_fullscreen(GLuint framebuffer, int width, int height) {
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
}

void draw_fullscreen_triangle(GLuint empty_vertex_array) {
    glBindVertexArray(empty_vertex_array);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

void draw_into_display(FrameResources& frame, const gl::Program& program) {
    begin_fullscreen(frame.display_framebuffer.get(), frame.settings->width,
                     frame.settings->height);
    glUseProgram(program.get());
    draw_fullscreen_triangle(frame.empty_vertex_array);
}

PassOutput display_output(const FrameResources& frame, std::string name) {
    return {.name = std::move(name),
            .texture = frame.display.get(),
            .width = frame.settings->width,
            .height = frame.settings->height,
            .decode = OutputDecode::unorm_rgb};
}

gl::Framebuffer framebuffer_for(const gl::Texture& texture, const char* what) {
    gl::Framebuffer framebuffer = gl::create_framebuffer();
    glNamedFramebufferTexture(framebuffer.get(), GL_COLOR_ATTACHMENT0, texture.get(), 0);
    gl::check_framebuffer(framebuffer, what);
    return framebuffer;
}

void label_texture(const gl::Texture& texture, std::string_view pass, std::string_view what) {
    const std::string label = fmt::format("{} {}", pass, what);
    glObjectLabel(GL_TEXTURE, texture.get(), -1, label.c_str());
}

}  // namespace deepgi
