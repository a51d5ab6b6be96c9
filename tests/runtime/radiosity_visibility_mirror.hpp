// CPU mirror of radiosity_visibility.glsl, on read-back inputs: whether the
// segment from a gathering point X to a sample Y is free of the stored
// surfaces, each taken as a solid from its depth to its back face (at least
// two steps deep; `thickness` deep where no back face lies behind it), that
// the segment's points at t = (k + 1/2) / steps lie behind by more than
// 1 mm per metre of depth. Written from docs/radiosity.md's statement of the
// test, with the test's own projection of a camera-space point to its pixel.
#pragma once

#include "sao_reference.hpp"

#include <glm/glm.hpp>

#include <array>
#include <cmath>

namespace deepgi::test {

struct VisibilityInputs {
    std::array<FloatImage, 2> depth;      // linear metres, 0 = no surface
    std::array<FloatImage, 2> normal;     // camera space
    std::array<FloatImage, 2> back_face;  // linear metres of the nearest back face, 0 = none
    glm::vec2 ray_scale{1.0f};            // camera-space x, y at unit depth of the buffer's edge
    float near_plane = 0.0f;
    int layers = 2;
    int steps = 0;
    float thickness = 0.0f;
};

inline bool sample_visible(const VisibilityInputs& in, glm::vec3 x, glm::vec3 y) {
    const int width = in.depth[0].width;
    const int height = in.depth[0].height;
    const glm::vec3 v = y - x;
    const float step_length = std::sqrt(glm::dot(v, v)) / float(in.steps);
    for (int k = 0; k < in.steps; ++k) {
        const glm::vec3 q = x + v * ((float(k) + 0.5f) / float(in.steps));
        const float z = -q.z;
        if (z <= in.near_plane) continue;
        const float at_x = (q.x / (z * in.ray_scale.x) * 0.5f + 0.5f) * float(width);
        const float at_y = (q.y / (z * in.ray_scale.y) * 0.5f + 0.5f) * float(height);
        if (at_x < 0.0f || at_y < 0.0f || at_x >= float(width) || at_y >= float(height)) continue;
        const int px = int(at_x);
        const int py = int(at_y);
        for (int j = 0; j < in.layers; ++j) {
            const float depth = in.depth[j].at(px, py, 0);
            if (depth <= 0.0f || z <= depth) continue;
            const float back = in.back_face[j].at(px, py, 0);
            const float solid_end = back > 0.0f
                                        ? std::max(back, depth + 2.0f * step_length)
                                        : depth + std::max(in.thickness, 2.0f * step_length);
            if (z >= solid_end) continue;
            const float ndc_x = (float(px) + 0.5f) / float(width) * 2.0f - 1.0f;
            const float ndc_y = (float(py) + 0.5f) / float(height) * 2.0f - 1.0f;
            const glm::vec3 surface(ndc_x * in.ray_scale.x * depth, ndc_y * in.ray_scale.y * depth,
                                    -depth);
            const glm::vec3 n(in.normal[j].at(px, py, 0), in.normal[j].at(px, py, 1),
                              in.normal[j].at(px, py, 2));
            if (glm::dot(q - surface, n) < -1.0e-3f * z) return false;
        }
    }
    return true;
}

}  // namespace deepgi::test
