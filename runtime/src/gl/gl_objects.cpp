#include "deepgi/gl_objects.hpp"

#include "deepgi/errors.hpp"

#include <fmt/format.h>

namespace deepgi::gl {

void destroy_texture(GLuint name) {
    glDeleteTextures(1, &name);
}
void destroy_buffer(GLuint name) {
    glDeleteBuffers(1, &name);
}
void destroy_framebuffer(GLuint name) {
    glDeleteFramebuffers(1, &name);
}
void destroy_vertex_array(GLuint name) {
    glDeleteVertexArrays(1, &name);
}
void destroy_program(GLuint name) {
    glDeleteProgram(name);
}
void destroy_shader(GLuint name) {
    glDeleteShader(name);
}
void destroy_query(GLuint name) {
    glDeleteQueries(1, &name);
}
void destroy_sampler(GLuint name) {
    glDeleteSamplers(1, &name);
}

Texture create_texture(GLenum target) {
    GLuint name = 0;
    glCreateTextures(target, 1, &name);
    return Texture(name);
}

Buffer create_buffer() {
    GLuint name = 0;
    glCreateBuffers(1, &name);
    return Buffer(name);
}

Framebuffer create_framebuffer() {
    GLuint name = 0;
    glCreateFramebuffers(1, &name);
    return Framebuffer(name);
}

VertexArray create_vertex_array() {
    GLuint name = 0;
    glCreateVertexArrays(1, &name);
    return VertexArray(name);
}

Sampler create_sampler() {
    GLuint name = 0;
    glCreateSamplers(1, &name);
    return Sampler(name);
}

Query create_query(GLenum target) {
    GLuint name = 0;
    glCreateQueries(target, 1, &name);
    return Query(name);
}

static void set_nearest_clamped(GLuint texture) {
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

Texture create_texture_array(GLenum internal_format, int width, int height, int layers) {
    Texture texture = create_texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(texture.get(), 1, internal_format, width, height, layers);
    set_nearest_clamped(texture.get());
    return texture;
}

Texture create_texture_2d(GLenum internal_format, int width, int height) {
    Texture texture = create_texture(GL_TEXTURE_2D);
    glTextureStorage2D(texture.get(), 1, internal_format, width, height);
    set_nearest_clamped(texture.get());
    return texture;
}

void check_framebuffer(const Framebuffer& framebuffer, const char* what) {
    GLenum status = glCheckNamedFramebufferStatus(framebuffer.get(), GL_DRAW_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        throw GraphicsError(
            fmt::format("framebuffer '{}' is incomplete (status 0x{:04x})", what, status));
    }
}

}  // namespace deepgi::gl
