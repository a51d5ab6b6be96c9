#include "deepgi/scene.hpp"

#include "deepgi/errors.hpp"

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <numbers>

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

namespace {

constexpr std::string_view pose_prefix = "pose:";
constexpr double degrees_per_radian = 180.0 / std::numbers::pi;

}  // namespace

Camera parse_camera_pose(std::string_view text) {
    auto fail = [&](std::string_view problem) {
        throw InputError(fmt::format("--camera '{}': {}", text, problem));
    };
    if (text.substr(0, pose_prefix.size()) != pose_prefix) fail("a pose starts with 'pose:'");
    std::string_view rest = text.substr(pose_prefix.size());
    // Doubles, so that degrees written by format_camera_pose convert back to
    // the very float of radians they came from.
    std::array<double, 7> values{};
    for (std::size_t i = 0; i < values.size(); ++i) {
        const std::size_t comma = rest.find(',');
        const std::string_view field = rest.substr(0, comma);
        const auto [end, error] =
            std::from_chars(field.data(), field.data() + field.size(), values[i]);
        if (field.empty() || error != std::errc() || end != field.data() + field.size() ||
            !std::isfinite(values[i]) || std::abs(values[i]) > 1e30)
            fail(
                fmt::format("value {} '{}' is not a finite number (pose:X,Y,Z,YAW,PITCH,FOVY,NEAR)",
                            i + 1, field));
        if ((comma == std::string_view::npos) != (i + 1 == values.size()))
            fail("expected 7 values: pose:X,Y,Z,YAW,PITCH,FOVY,NEAR (degrees, scene units)");
        rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    }
    if (!(values[4] > -90.0 && values[4] < 90.0))
        fail("PITCH must be between -90 and 90 degrees (exclusive)");
    if (!(values[5] > 0.0 && values[5] < 180.0))
        fail("FOVY must be between 0 and 180 degrees (exclusive)");
    if (!(values[6] > 0.0)) fail("NEAR must be > 0");
    Camera camera;
    camera.position = glm::vec3(float(values[0]), float(values[1]), float(values[2]));
    camera.yaw = float(values[3] / degrees_per_radian);
    camera.pitch = float(values[4] / degrees_per_radian);
    camera.vertical_fov = float(values[5] / degrees_per_radian);
    camera.near_plane = float(values[6]);
    return camera;
}

std::string format_camera_pose(const Camera& camera) {
    // 9 significant digits round-trip a float; 17 a double, whose conversion
    // back to radians then rounds to the same float.
    return fmt::format("pose:{:.9g},{:.9g},{:.9g},{:.17g},{:.17g},{:.17g},{:.9g}",
                       camera.position.x, camera.position.y, camera.position.z,
                       double(camera.yaw) * degrees_per_radian,
                       double(camera.pitch) * degrees_per_radian,
                       double(camera.vertical_fov) * degrees_per_radian, camera.near_plane);
}

Camera select_camera(const Scene& scene, std::string_view camera) {
    if (camera.empty()) return scene.default_camera;
    if (camera.substr(0, pose_prefix.size()) == pose_prefix) return parse_camera_pose(camera);
    return find_file_camera(scene, camera);
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
