#include "deepgi/scene_builder.hpp"

#include <cmath>

namespace deepgi {

int SceneBuilder::add_material(glm::vec3 base_colour, glm::vec3 emissive) {
    Material material;
    material.base_colour = glm::vec4(base_colour, 1.0f);
    material.emissive = emissive;
    materials_.push_back(material);
    return static_cast<int>(materials_.size()) - 1;
}

int SceneBuilder::add_mirror_material(glm::vec3 reflectance) {
    const int index = add_material(reflectance);
    materials_[std::size_t(index)].roughness = 0.0f;
    materials_[std::size_t(index)].metallic = 1.0f;
    return index;
}

void SceneBuilder::add_quad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 normal,
                            int material) {
    normal = glm::normalize(normal);
    if (glm::dot(glm::cross(b - a, c - a), normal) < 0.0f) std::swap(b, d);
    const auto base = static_cast<std::uint32_t>(vertices_.size());
    const glm::vec2 uvs[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const glm::vec3 corners[4] = {a, b, c, d};
    for (int i = 0; i < 4; ++i) vertices_.push_back(Vertex{corners[i], normal, uvs[i]});
    auto& indices = indices_by_material_[material];
    for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(base + i);
}

void SceneBuilder::add_box(glm::vec3 centre, glm::vec3 half_extent, int material, float yaw) {
    const float c = std::cos(yaw);
    const float s = std::sin(yaw);
    auto rotate = [&](glm::vec3 v) {
        return glm::vec3(c * v.x + s * v.z, v.y, -s * v.x + c * v.z);
    };
    auto corner = [&](float x, float y, float z) {
        return centre + rotate(glm::vec3(x, y, z) * half_extent);
    };
    for (int axis = 0; axis < 3; ++axis) {
        for (float side : {-1.0f, 1.0f}) {
            glm::vec3 normal(0.0f);
            normal[axis] = side;
            const int u = (axis + 1) % 3;
            const int v = (axis + 2) % 3;
            glm::vec3 p[4];
            const float us[4] = {-1, 1, 1, -1};
            const float vs[4] = {-1, -1, 1, 1};
            for (int i = 0; i < 4; ++i) {
                glm::vec3 local(0.0f);
                local[axis] = side;
                local[u] = us[i];
                local[v] = vs[i];
                p[i] = corner(local.x, local.y, local.z);
            }
            add_quad(p[0], p[1], p[2], p[3], rotate(normal), material);
        }
    }
}

void SceneBuilder::finish(Scene& scene) {
    scene.vertices = std::move(vertices_);
    scene.materials = std::move(materials_);
    scene.indices.clear();
    scene.batches.clear();
    for (auto& [material, indices] : indices_by_material_) {
        DrawBatch batch;
        batch.first_index = static_cast<std::uint32_t>(scene.indices.size());
        batch.index_count = static_cast<std::uint32_t>(indices.size());
        batch.material = material;
        scene.indices.insert(scene.indices.end(), indices.begin(), indices.end());
        scene.batches.push_back(batch);
    }
    scene.bounds = compute_bounds(scene.vertices);
}

}  // namespace deepgi
