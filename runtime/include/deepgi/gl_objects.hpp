#pragma once
// Move-only owners of GL object names, so every texture, buffer and program
// is released exactly once even when a pass is rebuilt or an exception unwinds.
#include <epoxy/gl.h>

#include <utility>

namespace deepgi::gl {

template <void (*Destroy)(GLuint)>
class Handle {
public:
    Handle() = default;
    explicit Handle(GLuint name) : name_(name) {}
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    Handle(Handle&& other) noexcept : name_(std::exchange(other.name_, 0)) {}
    Handle& operator=(Handle&& other) noexcept {
        if (this != &other) {
            reset();
            name_ = std::exchange(other.name_, 0);
        }
        return *this;
    }
    ~Handle() { reset(); }

    GLuint get() const { return name_; }
    explicit operator bool() const { return name_ != 0; }
    void reset() {
        if (name_ != 0) Destroy(name_);
        name_ = 0;
    }

private:
    GLuint name_ = 0;
};

void destroy_texture(GLuint name);
void destroy_buffer(GLuint name);
void destroy_framebuffer(GLuint name);
void destroy_vertex_array(GLuint name);
void destroy_program(GLuint name);
void destroy_shader(GLuint name);
void destroy_query(GLuint name);
void destroy_sampler(GLuint name);

using Texture = Handle<&destroy_texture>;
using Buffer = Handle<&destroy_buffer>;
using Framebuffer = Handle<&destroy_framebuffer>;
using VertexArray = Handle<&destroy_vertex_array>;
using Program = Handle<&destroy_program>;
using Shader = Handle<&destroy_shader>;
using Query = Handle<&destroy_query>;
using Sampler = Handle<&destroy_sampler>;

Texture create_texture(GLenum target);
Buffer create_buffer();
Framebuffer create_framebuffer();
VertexArray create_vertex_array();
Query create_query(GLenum target);
Sampler create_sampler();

// 2-D array texture with one mip level, nearest filtering, clamped edges.
Texture create_texture_array(GLenum internal_format, int width, int height, int layers);
Texture create_texture_2d(GLenum internal_format, int width, int height);

// Throws GraphicsError naming `what` if the framebuffer is incomplete.
void check_framebuffer(const Framebuffer& framebuffer, const char* what);

}  // namespace deepgi::gl
