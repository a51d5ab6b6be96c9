// The glTF loader's scene assembly state, shared by its two files:
// gltf_scene_build.cpp (primitives, node graph, materials, finishing) and
// gltf_cameras_lights.cpp (file cameras and the key light).
#pragma once

#include "gltf_internal.hpp"

#include <glm/glm.hpp>

#include <chrono>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace deepgi::gltf {

// True when every component is a finite float: a finite double such as
// 1e300 becomes infinity when converted, and renders black.
template <typename Vector>
bool finite_floats(const Vector& v) {
    for (int i = 0; i < Vector::length(); ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}

// The state of one build: the scene so far and what the warnings count.
// One member function per job; build_scene calls them in order.
struct SceneAssembly {
    SceneAssembly(const tinygltf::Model& source, const SceneLimits& scene_limits,
                  const std::string& display_name)
        : model(source), limits(scene_limits), reader(source, display_name) {}

    const tinygltf::Model& model;
    const SceneLimits& limits;
    GltfReader reader;
    Scene scene;
    // Material -1 (none) becomes the glTF default material, appended last.
    std::map<int, std::vector<std::uint32_t>> indices_by_material;
    std::map<int, int> texture_of_image;
    std::uint64_t triangles = 0;
    std::uint64_t skipped_points_and_lines = 0;
    std::uint64_t orthographic_cameras = 0;
    bool rolled_camera = false;
    bool have_key_light = false;
    std::vector<std::string> dropped_lights;
    std::uint64_t visits = 0;
    std::uint64_t instances = 0;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();

    void check_time() const;
    void add_primitive(const tinygltf::Primitive& primitive, const glm::mat4& transform);
    void add_camera(int camera_index, const std::string& node_name, const glm::mat4& transform);
    void add_light(int light_index, const glm::mat4& transform);
    void visit(int node_index, const glm::mat4& parent, int depth);
    void flatten();
    int use_texture(int texture_index, TextureSampler& sampler);
    void add_materials();
    void finish();
};

}  // namespace deepgi::gltf
