#pragma once
// PNG previews of the reference's float images, mapped to display the way
// deepgi's debug views show the same quantities (shaders/debug_view.frag), so
// that the truth can be looked at without an image tool.
#include "deepgi/image_io.hpp"

#include <cstdint>
#include <vector>

namespace deepgi_app {

enum class PreviewMapping {
    depth,       // linear depth: 1 - 0.9 depth / (the image's largest), black where nothing is hit
    unit,        // a value in [0, 1] (visibility, the occlusion split), clamped
    radiance,    // radiance through the filmic tonemap at exposure 1
    irradiance,  // E shown as the radiance of a white Lambertian surface, E / pi
    normalised,  // a count or an error: divided by the image's largest value
    identifier,  // the first channel as an id: a colour hashed from it; -1 dark blue, else < 0
                 // black
};

// RGBA8, rows bottom to top like the image (encode_png flips them); 1-channel
// images become grey. sRGB-encoded, as the debug views are.
std::vector<std::uint8_t> preview_rgba8(const deepgi::FloatImage& image, PreviewMapping mapping);

// Hable's filmic curve with the tonemap pass's white point and exposure bias
// (shaders/tonemap_curve.glsl), on one channel of linear radiance.
float filmic_tonemap(float radiance);

}  // namespace deepgi_app
