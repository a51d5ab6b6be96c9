// Reads a pass output back and decodes it into the float image --dump writes.
// Every pass describes its outputs (pass.hpp); this file is the only one that
// knows how each encoding becomes floats.
#include "pass.hpp"

#include "gl/readback.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace deepgi {

namespace {

glm::vec3 decode_octahedral_normal(float x, float y) {
    glm::vec3 n(x, y, 1.0f - std::abs(x) - std::abs(y));
    const float t = std::max(-n.z, 0.0f);
    n.x += n.x >= 0.0f ? -t : t;
    n.y += n.y >= 0.0f ? -t : t;
    return glm::normalize(n);
}

float srgb_decode(float encoded) {
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

FloatImage read_pass_output(const PassOutput& output, float near_plane) {
    const int w = output.width;
    const int h = output.height;
    const std::size_t pixels = std::size_t(w) * std::size_t(h);
    FloatImage image;
    image.width = w;
    image.height = h;
    image.channels = 3;
    switch (output.decode) {
        case OutputDecode::floats:
            image.channels = output.channels;
            image.pixels = gl::read_floats(output.texture, output.level, output.layer, w, h,
                                           output.channels == 1 ? GL_RED : GL_RGB, output.channels);
            break;
        case OutputDecode::alpha: {
            const auto rgba =
                gl::read_floats(output.texture, output.level, output.layer, w, h, GL_RGBA, 4);
            image.channels = 1;
            image.pixels.resize(pixels);
            for (std::size_t i = 0; i < pixels; ++i) image.pixels[i] = rgba[4 * i + 3];
            break;
        }
        case OutputDecode::floats_rg_as_rgb: {
            const auto rg =
                gl::read_floats(output.texture, output.level, output.layer, w, h, GL_RG, 2);
            image.pixels.assign(pixels * 3, 0.0f);
            for (std::size_t i = 0; i < pixels; ++i) {
                image.pixels[3 * i] = rg[2 * i];
                image.pixels[3 * i + 1] = rg[2 * i + 1];
            }
            break;
        }
        case OutputDecode::floats_ba_as_rgb: {
            const auto rgba =
                gl::read_floats(output.texture, output.level, output.layer, w, h, GL_RGBA, 4);
            image.pixels.assign(pixels * 3, 0.0f);
            for (std::size_t i = 0; i < pixels; ++i) {
                image.pixels[3 * i] = rgba[4 * i + 2];
                image.pixels[3 * i + 1] = rgba[4 * i + 3];
            }
            break;
        }
        case OutputDecode::depth_to_metres:
            image.channels = 1;
            image.pixels = gl::read_floats(output.texture, output.level, output.layer, w, h,
                                           GL_DEPTH_COMPONENT, 1);
            // Linear camera depth in metres; 0 where nothing was hit.
            for (float& value : image.pixels) value = value > 0.0f ? near_plane / value : 0.0f;
            break;
        case OutputDecode::octahedral_normal: {
            const auto encoded =
                gl::read_floats(output.texture, output.level, output.layer, w, h, GL_RG, 2);
            const auto depth =
                gl::read_floats(output.mask_depth, 0, output.layer, w, h, GL_DEPTH_COMPONENT, 1);
            image.pixels.assign(pixels * 3, 0.0f);
            for (std::size_t i = 0; i < pixels; ++i) {
                if (depth[i] <= 0.0f) continue;
                const glm::vec3 n = decode_octahedral_normal(encoded[2 * i], encoded[2 * i + 1]);
                image.pixels[3 * i] = n.x;
                image.pixels[3 * i + 1] = n.y;
                image.pixels[3 * i + 2] = n.z;
            }
            break;
        }
        case OutputDecode::srgb_to_linear:
        case OutputDecode::unorm_rgb: {
            const auto bytes = gl::read_rgba8(output.texture, output.layer, w, h);
            const bool srgb = output.decode == OutputDecode::srgb_to_linear;
            image.pixels.resize(pixels * 3);
            for (std::size_t i = 0; i < pixels; ++i) {
                for (std::size_t c = 0; c < 3; ++c) {
                    const float unorm = float(bytes[4 * i + c]) / 255.0f;
                    image.pixels[3 * i + c] = srgb ? srgb_decode(unorm) : unorm;
                }
            }
            break;
        }
        case OutputDecode::shadow_depth:
            image.channels = 1;
            glTextureParameteri(output.texture, GL_TEXTURE_COMPARE_MODE, GL_NONE);
            image.pixels = gl::read_floats(output.texture, 0, 0, w, h, GL_DEPTH_COMPONENT, 1);
            glTextureParameteri(output.texture, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
            break;
    }
    return image;
}

}  // namespace deepgi
