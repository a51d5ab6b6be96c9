#pragma once
// A CPU ray cast of the scene triangles: the independent oracle for the
// G-buffer.
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "support/runtime_support.hpp"
#include "support/textbook_camera.hpp"

#include <glm/glm.hpp>

#include <cmath>
#include <limits>
#include <vector>

namespace deepgi::test {

struct RayHits {
    float layer0 = 0.0f;  // linear camera depth, 0 for none
    float layer1 = 0.0f;
    int triangle0 = -1;
    int triangle1 = -1;
};

// Camera-space ray through an internal (guard-banded) pixel position, with
// z = -1 so the hit parameter t equals the linear camera depth. The camera is
// the textbook one (support/textbook_camera.hpp), not the library's matrices.
inline glm::vec3 camera_ray(const Camera& camera, const RenderSettings& settings, float px,
                            float py) {
    return textbook_camera_ray(textbook_camera(camera, settings), px, py);
}

// Front faces only (counter-clockwise), as the G-buffer culls back faces.
inline RayHits ray_cast(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                        float px, float py, float min_separation) {
    const TextbookCamera textbook = textbook_camera(camera, settings);
    const glm::vec3 origin = camera.position;
    const glm::vec3 direction = textbook_to_world(textbook, textbook_camera_ray(textbook, px, py));
    std::vector<std::pair<float, int>> hits;
    for (std::size_t t = 0; t + 2 < scene.indices.size(); t += 3) {
        const glm::vec3 a = scene.vertices[scene.indices[t]].position;
        const glm::vec3 b = scene.vertices[scene.indices[t + 1]].position;
        const glm::vec3 c = scene.vertices[scene.indices[t + 2]].position;
        const glm::vec3 e1 = b - a;
        const glm::vec3 e2 = c - a;
        if (glm::dot(glm::cross(e1, e2), direction) >= 0.0f) continue;  // back face or edge-on
        const glm::vec3 p = glm::cross(direction, e2);
        const float determinant = glm::dot(e1, p);
        const glm::vec3 s = origin - a;
        const float u = glm::dot(s, p) / determinant;
        if (u < 0.0f || u > 1.0f) continue;
        const glm::vec3 q = glm::cross(s, e1);
        const float v = glm::dot(direction, q) / determinant;
        if (v < 0.0f || u + v > 1.0f) continue;
        const float distance = glm::dot(e2, q) / determinant;
        if (distance > camera.near_plane) hits.push_back({distance, int(t / 3)});
    }
    RayHits result;
    float nearest = std::numeric_limits<float>::infinity();
    for (auto [distance, triangle] : hits) {
        if (distance < nearest) {
            nearest = distance;
            result.layer0 = distance;
            result.triangle0 = triangle;
        }
    }
    if (result.triangle0 < 0) return result;
    float second = std::numeric_limits<float>::infinity();
    for (auto [distance, triangle] : hits) {
        if (distance >= result.layer0 + min_separation && distance < second) {
            second = distance;
            result.layer1 = distance;
            result.triangle1 = triangle;
        }
    }
    return result;
}

}  // namespace deepgi::test
