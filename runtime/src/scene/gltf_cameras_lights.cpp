// The glTF loader's cameras and key light: the file's perspective cameras
// as the renderer's levelled camera, and the first KHR_lights_punctual light
// as its key light, every value checked as the renderer will use it.
#include "gltf_assembly.hpp"

#include <algorithm>
#include <cmath>

namespace deepgi::gltf {

// A glTF camera looks down its local -Z with +Y up. The renderer's camera
// has no roll and takes its aspect from the output size, so both are
// reported when the file's differ.
void SceneAssembly::add_camera(int camera_index, const std::string& node_name,
                               const glm::mat4& transform) {
    const auto& source = model.cameras[std::size_t(camera_index)];
    if (source.type != "perspective") {
        ++orthographic_cameras;
        return;
    }
    const glm::vec3 forward = glm::mat3(transform) * glm::vec3(0, 0, -1);
    const glm::vec3 up = glm::mat3(transform) * glm::vec3(0, 1, 0);
    const float forward_length = glm::length(forward);
    const double yfov = source.perspective.yfov;
    const double znear = source.perspective.znear;
    if (!(forward_length > 0.0f) || !std::isfinite(forward_length))
        reader.fail(fmt::format("camera {} has a degenerate node transform", camera_index));
    if (!(yfov > 0.0 && yfov < 3.14159) || !(znear > 0.0) || !std::isfinite(znear))
        reader.fail(
            fmt::format("camera {}: yfov must lie in (0, pi) and znear be > 0", camera_index));
    // The renderer works in float: 1e-300 becomes 0 and 1e39 infinity, and
    // the projection divides by tan(yfov / 2).
    if (!std::isnormal(float(yfov)) || !std::isfinite(1.0f / std::tan(float(yfov) * 0.5f)) ||
        !std::isnormal(float(znear)))
        reader.fail(
            fmt::format("camera {}: yfov {} or znear {} is outside the renderer's float range",
                        camera_index, yfov, znear));
    const glm::vec3 f = forward / forward_length;
    FileCamera file_camera;
    file_camera.index = camera_index;
    file_camera.name = source.name.empty() ? node_name : source.name;
    file_camera.camera.position = glm::vec3(transform * glm::vec4(0, 0, 0, 1));
    file_camera.camera.yaw = std::atan2(f.x, -f.z);
    file_camera.camera.pitch = std::asin(std::clamp(f.y, -1.0f, 1.0f));
    file_camera.camera.vertical_fov = float(yfov);
    file_camera.camera.near_plane = float(znear);
    const glm::vec3 right = glm::cross(f, glm::vec3(0, 1, 0));
    if (glm::length(right) > 1e-6f) {
        const glm::vec3 level_up = glm::normalize(glm::cross(glm::normalize(right), f));
        if (glm::dot(glm::normalize(up), level_up) < 0.9999f) rolled_camera = true;
    }
    scene.file_cameras.push_back(file_camera);
}

// KHR_lights_punctual: the renderer has one key light, directional, spot
// or point. The first light met walking the nodes is it; every further
// placement is named as dropped. The
// extension's photometric units (lux, candela) become the renderer's
// radiometric ones through 683 lm/W, the luminous efficacy the
// extension's units are defined against.
void SceneAssembly::add_light(int light_index, const glm::mat4& transform) {
    const auto& light = model.lights[std::size_t(light_index)];
    const std::string label = fmt::format(
        "{}{}", light_index, light.name.empty() ? "" : fmt::format(" '{}'", light.name));
    if (light.type != "directional" && light.type != "spot" && light.type != "point") {
        dropped_lights.push_back(fmt::format("{} ({}: unknown type)", label, light.type));
        return;
    }
    if (have_key_light) {
        dropped_lights.push_back(fmt::format("{} ({}, one key light only)", label, light.type));
        return;
    }
    const glm::vec3 direction = glm::mat3(transform) * glm::vec3(0, 0, -1);
    const float length = glm::length(direction);
    if (!(length > 0.0f) || !std::isfinite(length))
        reader.fail(fmt::format("light {} has a degenerate node transform", light_index));
    if (!(light.intensity >= 0.0) || !std::isfinite(light.intensity))
        reader.fail(fmt::format("light {}: intensity must be a finite number >= 0", light_index));
    KeyLight key;
    key.kind = light.type == "spot"    ? LightKind::spot
               : light.type == "point" ? LightKind::point
                                       : LightKind::directional;
    key.direction = direction / length;
    key.position = glm::vec3(transform * glm::vec4(0, 0, 0, 1));
    key.colour = light.color.size() == 3 ? glm::vec3(light.color[0], light.color[1], light.color[2])
                                         : glm::vec3(1.0f);
    key.intensity = float(light.intensity / 683.0);
    // Checked as the renderer uses them, in float and multiplied together.
    if (!finite_floats(key.colour) || key.colour.r < 0.0f || key.colour.g < 0.0f ||
        key.colour.b < 0.0f || !std::isfinite(key.intensity) ||
        !finite_floats(key.colour * key.intensity))
        reader.fail(fmt::format(
            "light {}: colour x intensity must be >= 0 and finite as float (colour {}, "
            "intensity {})",
            light_index,
            light.color.size() == 3
                ? fmt::format("[{}, {}, {}]", light.color[0], light.color[1], light.color[2])
                : std::string("default"),
            light.intensity));
    if (key.kind == LightKind::spot) {
        const double inner = light.spot.innerConeAngle, outer = light.spot.outerConeAngle;
        if (!(inner >= 0.0 && inner < outer && outer <= 1.5707963268))
            reader.fail(fmt::format("light {}: spot cone angles need 0 <= inner < outer <= pi/2",
                                    light_index));
        key.inner_cone = float(inner);
        key.outer_cone = float(outer);
    }
    if (key.kind != LightKind::directional && light.range != 0.0) {
        if (!(light.range > 0.0) || !std::isfinite(light.range))
            reader.fail(fmt::format("light {}: range must be a finite number > 0", light_index));
        key.range = float(light.range);
        if (!std::isfinite(key.range))
            reader.fail(
                fmt::format("light {}: range {} overflows a float", light_index, light.range));
    }
    scene.key_light = key;
    have_key_light = true;
}

}  // namespace deepgi::gltf
