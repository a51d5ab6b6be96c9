#include "deepgi/scene.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace deepgi {

glm::vec3 camera_forward(const Camera& camera) {
    return {std::cos(camera.pitch) * std::sin(camera.yaw), std::sin(camera.pitch),
            -std::cos(camera.pitch) * std::cos(camera.yaw)};
}

glm::mat4 camera_view_matrix(const Camera& camera) {
    // Orient at the origin, then translate. lookAt(p, p + forward) would round
    // p + forward to the spacing of p's floats and take the direction back out
    // of that difference: a camera 1 km from the origin then looks about 1e-4
    // rad off, which moves depths far more than float rounding otherwise does.
    const glm::mat4 rotation =
        glm::lookAt(glm::vec3(0.0f), camera_forward(camera), glm::vec3(0, 1, 0));
    return glm::translate(rotation, -camera.position);
}

Camera camera_on_path(const CameraPath& path, int frame) {
    if (path.keys.empty()) return {};
    if (path.keys.size() == 1 || path.frames_per_key <= 0) return path.keys.front();
    const int key_count = static_cast<int>(path.keys.size());
    const int cycle = key_count * path.frames_per_key;
    const int wrapped = ((frame % cycle) + cycle) % cycle;
    const int key = wrapped / path.frames_per_key;
    const float t = float(wrapped % path.frames_per_key) / float(path.frames_per_key);
    // Smoothstep blend: the camera eases in and out of every key.
    const float s = t * t * (3.0f - 2.0f * t);
    const Camera& a = path.keys[static_cast<std::size_t>(key)];
    const Camera& b = path.keys[static_cast<std::size_t>((key + 1) % key_count)];
    Camera camera = a;
    camera.position = glm::mix(a.position, b.position, s);
    camera.yaw = a.yaw + (b.yaw - a.yaw) * s;
    camera.pitch = a.pitch + (b.pitch - a.pitch) * s;
    return camera;
}

Bounds compute_bounds(const std::vector<Vertex>& vertices) {
    Bounds bounds;
    if (vertices.empty()) return bounds;
    bounds.min = bounds.max = vertices.front().position;
    for (const auto& vertex : vertices) {
        bounds.min = glm::min(bounds.min, vertex.position);
        bounds.max = glm::max(bounds.max, vertex.position);
    }
    return bounds;
}

}  // namespace deepgi
