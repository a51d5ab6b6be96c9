#include "gl/readback.hpp"

namespace deepgi::gl {

std::vector<float> read_floats(GLuint texture, int level, int layer, int width, int height,
                               GLenum format, int components) {
    std::vector<float> values(std::size_t(width) * std::size_t(height) * std::size_t(components));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureSubImage(texture, level, 0, 0, layer, width, height, 1, format, GL_FLOAT,
                         GLsizei(values.size() * sizeof(float)), values.data());
    return values;
}

std::vector<std::uint8_t> read_rgba8(GLuint texture, int layer, int width, int height) {
    std::vector<std::uint8_t> values(std::size_t(width) * std::size_t(height) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureSubImage(texture, 0, 0, 0, layer, width, height, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                         GLsizei(values.size()), values.data());
    return values;
}

}  // namespace deepgi::gl
