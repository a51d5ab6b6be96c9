// Small scenes built by hand for the runtime tests, each shared by the test
// files that use it, so that a scene's geometry is written once and every
// expectation can be worked out from it; and the read-back helper that
// places a pixel of such a scene in the world.
#pragma once

#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/scene_builder.hpp"
#include "sao_reference.hpp"

#include <glm/glm.hpp>

namespace deepgi::test {

// A camera at the origin looking down -Z (the library's Camera otherwise).
inline Camera camera_at_origin(float fov_degrees = 60.0f, float near_plane = 0.05f) {
    Camera camera;
    camera.vertical_fov = glm::radians(fov_degrees);
    camera.near_plane = near_plane;
    return camera;  // at the origin, looking down -Z
}

// The floor y = -1 under a camera at the origin: 40 m wide (x in [-20, 20])
// and 45 m deep (z from 5 to -40), facing +y. The SAO, radiosity and
// alpha-mask tests stand their columns, boxes and banners on it.
inline void add_floor_below_origin(SceneBuilder& builder, int material) {
    builder.add_quad({-20, -1, 5}, {20, -1, 5}, {20, -1, -40}, {-20, -1, -40}, {0, 1, 0}, material);
}

// A white quad facing +Z at z = -distance, wide enough to fill any view.
inline Scene camera_facing_plane(float distance) {
    Scene scene;
    scene.name = "test-plane";
    SceneBuilder builder;
    const int white = builder.add_material({0.8f, 0.8f, 0.8f});
    const float extent = 100.0f * distance;
    builder.add_quad({-extent, -extent, -distance}, {extent, -extent, -distance},
                     {extent, extent, -distance}, {-extent, extent, -distance}, {0, 0, 1}, white);
    builder.finish(scene);
    scene.default_camera = camera_at_origin();
    scene.camera_path.keys = {scene.default_camera};
    return scene;
}

// A floor (y = -1) under a camera at the origin, with a wall and blocks on it,
// some boxes hidden behind others so layer 1 has surfaces to offer; optionally
// a quad just beyond the near plane.
inline Scene occluded_floor(bool with_near_quad = false) {
    Scene scene;
    scene.name = "test-floor";
    SceneBuilder builder;
    const int white = builder.add_material({0.8f, 0.8f, 0.8f});
    add_floor_below_origin(builder, white);
    builder.add_quad({-20, -1, -6}, {20, -1, -6}, {20, 6, -6}, {-20, 6, -6}, {0, 0, 1}, white);
    builder.add_box({-0.8f, -0.4f, -3.0f}, {0.5f, 0.6f, 0.5f}, white, 0.3f);
    builder.add_box({-0.8f, -0.7f, -4.2f}, {0.3f, 0.3f, 0.3f},
                    white);  // partly behind the first box
    builder.add_box({1.2f, -0.2f, -4.0f}, {0.3f, 0.8f, 0.3f}, white, -0.5f);
    builder.add_box({1.0f, -0.8f, -5.0f}, {0.6f, 0.2f, 0.4f}, white);
    if (with_near_quad) {
        builder.add_quad({-0.2f, -0.2f, -0.06f}, {0.1f, -0.2f, -0.06f}, {0.1f, 0.1f, -0.051f},
                         {-0.2f, 0.1f, -0.051f}, {0, 0, 1}, white);
    }
    builder.finish(scene);
    scene.default_camera = camera_at_origin();
    scene.default_camera.pitch = glm::radians(-15.0f);
    scene.camera_path.keys = {scene.default_camera};
    return scene;
}

// World position of layer 0's point at pixel (x, y), from read-back depth
// (metres along the view axis, the dump's `gbuffer-depth-layer0`).
inline glm::vec3 world_point(const FloatImage& depth, const Camera& camera,
                             const RenderSettings& settings, int x, int y) {
    const glm::vec2 ray = camera_ray_scale(camera, settings);
    const float d = depth.at(x, y, 0);
    const float ndc_x = (float(x) + 0.5f) / float(depth.width) * 2.0f - 1.0f;
    const float ndc_y = (float(y) + 0.5f) / float(depth.height) * 2.0f - 1.0f;
    const glm::vec4 camera_space(ndc_x * ray.x * d, ndc_y * ray.y * d, -d, 1.0f);
    return glm::vec3(glm::inverse(camera_view_matrix(camera)) * camera_space);
}

}  // namespace deepgi::test
