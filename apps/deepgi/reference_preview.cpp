#include "reference_preview.hpp"

#include <algorithm>
#include <cmath>

namespace deepgi_app {
namespace {

float filmic_curve(float x) {
    const float shoulder = 0.15f, linear_strength = 0.50f, linear_angle = 0.10f;
    const float toe = 0.20f, toe_numerator = 0.02f, toe_denominator = 0.30f;
    return (x * (shoulder * x + linear_angle * linear_strength) + toe * toe_numerator) /
               (x * (shoulder * x + linear_strength) + toe * toe_denominator) -
           toe_numerator / toe_denominator;
}

std::uint8_t srgb_byte(float linear) {
    const float c = std::clamp(std::isfinite(linear) ? linear : 0.0f, 0.0f, 1.0f);
    const float encoded = c < 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return std::uint8_t(std::lround(encoded * 255.0f));
}

// A bright colour per id, so neighbouring surfaces tell apart.
float identifier_colour(float id, int channel) {
    if (!(id >= 0.0f)) return id == -1.0f && channel == 2 ? 0.25f : 0.0f;
    std::uint32_t h = std::uint32_t(id) * 0x9e3779b1u;
    h ^= h >> 15;
    h *= 0x85ebca77u;
    h ^= h >> 13;
    return 0.2f + 0.8f * float((h >> (8 * channel)) & 0xffu) / 255.0f;
}

}  // namespace

float filmic_tonemap(float radiance) {
    const float white_point = 11.2f, exposure_bias = 2.0f;
    return std::clamp(filmic_curve(radiance * exposure_bias) / filmic_curve(white_point), 0.0f,
                      1.0f);
}

std::vector<std::uint8_t> preview_rgba8(const deepgi::FloatImage& image, PreviewMapping mapping) {
    float largest = 0.0f;
    for (float value : image.pixels)
        if (std::isfinite(value)) largest = std::max(largest, value);
    const std::size_t count = std::size_t(image.width) * std::size_t(image.height);
    std::vector<std::uint8_t> rgba(count * 4, 255);
    for (std::size_t i = 0; i < count; ++i) {
        for (int c = 0; c < 3; ++c) {
            const float value = image.pixels[i * std::size_t(image.channels) +
                                             std::size_t(image.channels == 3 ? c : 0)];
            float shown = 0.0f;
            switch (mapping) {
                case PreviewMapping::depth:
                    // The farthest surface stays a little above the black of "nothing hit".
                    shown = value > 0.0f && largest > 0.0f ? 1.0f - 0.9f * value / largest : 0.0f;
                    break;
                case PreviewMapping::unit:
                    shown = value;
                    break;
                case PreviewMapping::radiance:
                    shown = filmic_tonemap(value);
                    break;
                case PreviewMapping::irradiance:
                    shown = filmic_tonemap(value * 0.31830989f);
                    break;
                case PreviewMapping::normalised:
                    shown = largest > 0.0f ? value / largest : 0.0f;
                    break;
                case PreviewMapping::identifier:
                    shown = identifier_colour(image.pixels[i * std::size_t(image.channels)], c);
                    break;
            }
            rgba[i * 4 + std::size_t(c)] = srgb_byte(shown);
        }
    }
    return rgba;
}

}  // namespace deepgi_app
