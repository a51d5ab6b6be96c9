// CPU mirror of radiosity_visibility.glsl, on read-back inputs: whether the
// segment from a gathering point X to a sample Y is free of the stored
// surfaces, each taken as a solid from its depth to its back face
// (`thickness` deep where no back face lies behind it), that the segment's
// points at t = (k + 1/2) / steps lie behind by more than 1 mm per metre of
// depth; a point past that solid but within two steps of its front is hidden
// only where the segment left the camera's sight through a surface, not
// behind an edge. Written from docs/radiosity.md's statement of the
// test, with the test's own projection of a camera-space point to its pixel.
#pragma once

#include "sao_reference.hpp"
#include "radiosity_visibility_constants.h"

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

// The pixel of camera-space point c, or (-1, -1) outside the buffer or before
// the near plane.
inline glm::ivec2 visibility_pixel(const VisibilityInputs& in, glm::vec3 c) {
    const int width = in.depth[0].width;
    const int height = in.depth[0].height;
    const float z = -c.z;
    if (z <= in.near_plane) return glm::ivec2(-1);
    const float at_x = (c.x / (z * in.ray_scale.x) * 0.5f + 0.5f) * float(width);
    const float at_y = (c.y / (z * in.ray_scale.y) * 0.5f + 0.5f) * float(height);
    if (at_x < 0.0f || at_y < 0.0f || at_x >= float(width) || at_y >= float(height))
        return glm::ivec2(-1);
    return {int(at_x), int(at_y)};
}

// The stored point of layer j at pixel p, at `depth`, and its normal.
inline glm::vec3 stored_point(const VisibilityInputs& in, glm::ivec2 p, float depth) {
    const float ndc_x = (float(p.x) + 0.5f) / float(in.depth[0].width) * 2.0f - 1.0f;
    const float ndc_y = (float(p.y) + 0.5f) / float(in.depth[0].height) * 2.0f - 1.0f;
    return {ndc_x * in.ray_scale.x * depth, ndc_y * in.ray_scale.y * depth, -depth};
}

inline glm::vec3 stored_normal(const VisibilityInputs& in, glm::ivec2 p, int j) {
    return {in.normal[j].at(p.x, p.y, 0), in.normal[j].at(p.x, p.y, 1),
            in.normal[j].at(p.x, p.y, 2)};
}

// Whether the camera sees c: before layer 0's depth at its pixel, or nothing
// stored there.
inline bool point_seen(const VisibilityInputs& in, glm::vec3 c) {
    const glm::ivec2 p = visibility_pixel(in, c);
    if (p.x < 0) return true;
    const float depth = in.depth[0].at(p.x, p.y, 0);
    return depth <= 0.0f || -c.z < depth;
}

// The segment is seen at a and hidden at b: whether it leaves the camera's
// sight through the surface layer 0 stores (within b's distance to a, two
// pixels' footprint and 1 mm per metre of its plane, after
// DEEPGI_RADIOSITY_CROSSING_HALVINGS halvings
// of a to b) rather than behind an edge of it.
inline bool segment_enters_surface(const VisibilityInputs& in, glm::vec3 a, glm::vec3 b) {
    for (int i = 0; i < DEEPGI_RADIOSITY_CROSSING_HALVINGS; ++i) {
        const glm::vec3 m = 0.5f * (a + b);
        if (point_seen(in, m))
            a = m;
        else
            b = m;
    }
    const glm::ivec2 p = visibility_pixel(in, b);
    if (p.x < 0) return false;
    const float depth = in.depth[0].at(p.x, p.y, 0);
    if (depth <= 0.0f) return false;
    const float z = -b.z;
    const float footprint = 2.0f * in.ray_scale.y / float(in.depth[0].height) * z;
    return glm::dot(b - stored_point(in, p, depth), stored_normal(in, p, 0)) >=
           -(glm::length(b - a) + 2.0f * footprint + 1.0e-3f * z);
}

inline bool sample_visible(const VisibilityInputs& in, glm::vec3 x, glm::vec3 y) {
    const glm::vec3 v = y - x;
    const float step_length = std::sqrt(glm::dot(v, v)) / float(in.steps);
    glm::vec3 last_seen = x;
    for (int k = 0; k < in.steps; ++k) {
        const glm::vec3 q = x + v * ((float(k) + 0.5f) / float(in.steps));
        const float z = -q.z;
        const glm::ivec2 p = visibility_pixel(in, q);
        if (p.x < 0) continue;
        bool suspect = false;
        for (int j = 0; j < in.layers; ++j) {
            const float depth = in.depth[j].at(p.x, p.y, 0);
            if (depth <= 0.0f || z <= depth) continue;
            const float back = in.back_face[j].at(p.x, p.y, 0);
            const float stored_end = back > 0.0f ? back : depth + in.thickness;
            if (z >= std::max(stored_end, depth + 2.0f * step_length)) continue;
            if (glm::dot(q - stored_point(in, p, depth), stored_normal(in, p, j)) >= -1.0e-3f * z)
                continue;
            if (z < stored_end) return false;
            suspect = true;
        }
        if (suspect && segment_enters_surface(in, last_seen, q)) return false;
        const float front = in.depth[0].at(p.x, p.y, 0);
        if (front <= 0.0f || z < front) last_seen = q;
    }
    return true;
}

}  // namespace deepgi::test
