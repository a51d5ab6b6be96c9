#pragma once
// Reading textures back to the CPU (dumps, tests). Slow by design: each call
// waits for the GPU.
#include <epoxy/gl.h>

#include <cstdint>
#include <vector>

namespace deepgi::gl {

// `components` floats per pixel of one layer (array textures) or the texture.
std::vector<float> read_floats(GLuint texture, int level, int layer, int width, int height,
                               GLenum format, int components);
// RGBA8 bytes of one layer.
std::vector<std::uint8_t> read_rgba8(GLuint texture, int layer, int width, int height);

}  // namespace deepgi::gl
