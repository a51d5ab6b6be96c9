// A camera built from the textbook formulas, for the oracles of the runtime
// tests (the CPU ray cast, the motion-vector oracle, the reference tests), so
// they do not reuse the library's camera_view_matrix / guard_band_projection
// they are meant to check.
//
// From the definitions only (runtime/include/deepgi/scene.hpp, docs/design.md):
// - look-at: yaw turns about +Y, 0 looks down -Z; pitch > 0 looks up, so the
//   forward axis is (sin yaw cos pitch, sin pitch, -cos yaw cos pitch); right
//   = forward x world up, normalised; up = right x forward;
// - perspective: the viewport's height spans the vertical field of view, so a
//   point at depth d along forward and height h above the axis sits
//   h / (d tan(fov / 2)) half-heights above the viewport's centre; square
//   pixels;
// - guard band: round(fraction * height) pixels of the same projection around
//   the viewport on every side; "internal" pixels count from the guard band's
//   lower left corner, pixel centres at +1/2.
#pragma once

#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"

#include <glm/glm.hpp>

#include <cmath>

namespace deepgi::test {

struct TextbookCamera {
    glm::vec3 eye{0.0f};
    glm::vec3 right{1, 0, 0}, up{0, 1, 0}, forward{0, 0, -1};
    float tan_half_fov = 1.0f;
    int width = 1, height = 1;  // viewport pixels
    int guard = 0;              // guard band pixels on every side
};

inline TextbookCamera textbook_camera(const Camera& camera, const RenderSettings& settings) {
    TextbookCamera t;
    t.eye = camera.position;
    const double cy = std::cos(double(camera.yaw)), sy = std::sin(double(camera.yaw));
    const double cp = std::cos(double(camera.pitch)), sp = std::sin(double(camera.pitch));
    t.forward = glm::vec3(float(sy * cp), float(sp), float(-cy * cp));
    t.right = glm::normalize(glm::cross(t.forward, glm::vec3(0, 1, 0)));
    t.up = glm::cross(t.right, t.forward);
    t.tan_half_fov = float(std::tan(0.5 * double(camera.vertical_fov)));
    t.width = settings.width;
    t.height = settings.height;
    t.guard = int(std::lround(double(settings.guard_band_fraction) * double(settings.height)));
    return t;
}

// Camera-space direction (x right, y up, z = -1 forward) through an internal
// pixel position, so a hit at parameter t lies at linear depth t.
inline glm::vec3 textbook_camera_ray(const TextbookCamera& t, float px, float py) {
    const float half = 0.5f * float(t.height);
    const float x = (px - float(t.guard) - 0.5f * float(t.width)) / half * t.tan_half_fov;
    const float y = (py - float(t.guard) - 0.5f * float(t.height)) / half * t.tan_half_fov;
    return {x, y, -1.0f};
}

// A camera-space vector in world space.
inline glm::vec3 textbook_to_world(const TextbookCamera& t, glm::vec3 camera_space) {
    return t.right * camera_space.x + t.up * camera_space.y - t.forward * camera_space.z;
}

// A world direction in camera space (x right, y up, -z forward).
inline glm::vec3 textbook_direction_to_camera(const TextbookCamera& t, glm::vec3 world) {
    return {glm::dot(world, t.right), glm::dot(world, t.up), -glm::dot(world, t.forward)};
}

// A world point in camera space.
inline glm::vec3 textbook_point_to_camera(const TextbookCamera& t, glm::vec3 world) {
    return textbook_direction_to_camera(t, world - t.eye);
}

// A world point's internal pixel position and its linear depth (<= 0: behind
// the eye).
struct TextbookProjection {
    glm::vec2 pixel{0.0f};
    float depth = 0.0f;
};

inline TextbookProjection textbook_project(const TextbookCamera& t, glm::vec3 world) {
    const glm::vec3 v = world - t.eye;
    TextbookProjection p;
    p.depth = glm::dot(v, t.forward);
    const float half = 0.5f * float(t.height);
    const float scale = half / (p.depth * t.tan_half_fov);
    p.pixel = {float(t.guard) + 0.5f * float(t.width) + glm::dot(v, t.right) * scale,
               float(t.guard) + 0.5f * float(t.height) + glm::dot(v, t.up) * scale};
    return p;
}

}  // namespace deepgi::test
