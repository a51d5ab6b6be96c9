// Quads for the reference tests' hand-built scenes: p0 p1 p2 p3
// counter-clockwise seen from the side the quad faces, flat normal.
#pragma once

#include "deepgi/scene.hpp"

#include <glm/glm.hpp>

#include <cstdint>

namespace deepgi::test {

// Geometry only: the quad joins the scene's last batch.
inline void add_quad(Scene& scene, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3) {
    const auto base = std::uint32_t(scene.vertices.size());
    const glm::vec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    for (glm::vec3 p : {p0, p1, p2, p3}) scene.vertices.push_back({p, n, {0, 0}});
    for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) scene.indices.push_back(base + i);
}

// The quad in a batch of its own, with a new material of this albedo and
// emission.
inline void add_quad(Scene& scene, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3,
                     glm::vec3 albedo, glm::vec3 emissive) {
    Material material;
    material.base_colour = glm::vec4(albedo, 1.0f);
    material.emissive = emissive;
    scene.batches.push_back({std::uint32_t(scene.indices.size()), 6u, int(scene.materials.size())});
    scene.materials.push_back(material);
    add_quad(scene, p0, p1, p2, p3);
}

}  // namespace deepgi::test
