#pragma once
// CPU evaluation of the separable bilateral blur (bilateral_blur.frag),
// written from its formula as the oracle blur_test.cpp compares the pass
// with, and the hand-made guides (depth and normal per pixel) it reads.
#include "deepgi/settings.hpp"

#include <spiral/codegen.hpp>

#include <glm/glm.hpp>

#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

namespace deepgi::test {

// What the blur reads besides its source: layer-0 depth and normal per pixel.
struct Guide {
    int width = 0;
    int height = 0;
    std::vector<float> depth;       // metres, 0 = no surface
    std::vector<glm::vec3> normal;  // camera space, unit
    float at_depth(int x, int y) const {
        return depth[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    }
};

// A guide of width x height whose pixel (x, y) holds surface(x, y): its
// depth and its (not yet unit) normal.
Guide make_guide(int width, int height,
                 const std::function<std::pair<float, glm::vec3>(int, int)>& surface);

// Octahedral encoding, as gbuffer_encoding.glsl stores normals.
glm::vec2 encode_octahedral(glm::vec3 n);

// A source image: `channels` (1 or 4) floats per pixel.
struct Signal {
    int channels = 1;
    std::vector<float> values;
};

// CPU evaluation of the separable bilateral blur, horizontal then vertical,
// every source with the same weights:
//   out = (w_0 v_0 + sum_k w_k g_d g_n g_p v_k) / (w_0 + sum_k w_k g_d g_n g_p)
//   g_d = max(0, 1 - |d_k - d| / (t_d d)), g_n = max(n_k.n, 0)^p,
//   g_p = max(0, 1 - |(P_k - P).n| / (t_p d)),
//   g_e = max(0, 1 - |P_k - P|^2 / e^2) (1 when e = 0, no world extent);
// sky (d = 0) passes through and is never a tap. Positions use the camera
// ray scale (0.7, 0.45) that blur_test.cpp gives the pass; normals are
// decoded as the shader reads them from RG16F.
std::vector<Signal> cpu_blur(const Guide& guide, std::vector<Signal> sources,
                             const spiral::codegen::BlurKernel& kernel,
                             const BlurSettings& parameters = {}, double world_extent = 0.0);

}  // namespace deepgi::test
