#pragma once
// Builds procedural scenes (the built-in ones, the reference scenes, the
// report's hard cases): quads and boxes with outward faces,
// gathered per material and packed into one index range per material.
#include "deepgi/scene.hpp"

#include <map>

namespace deepgi {

class SceneBuilder {
public:
    int add_material(glm::vec3 base_colour, glm::vec3 emissive = glm::vec3(0.0f));
    // A polished metal: roughness 0, metallic 1, `reflectance` as its base colour.
    int add_mirror_material(glm::vec3 reflectance);

    // Corners in any order around the quad; the winding is chosen so that the
    // front face points along `normal`.
    void add_quad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 normal,
                  int material);

    // Axis-aligned box rotated by `yaw` radians about its vertical axis; six
    // outward faces.
    void add_box(glm::vec3 centre, glm::vec3 half_extent, int material, float yaw = 0.0f);

    // Moves the collected geometry into `scene` (vertices, indices, batches,
    // materials, bounds).
    void finish(Scene& scene);

private:
    std::vector<Material> materials_;
    std::vector<Vertex> vertices_;
    std::map<int, std::vector<std::uint32_t>> indices_by_material_;
};

}  // namespace deepgi
