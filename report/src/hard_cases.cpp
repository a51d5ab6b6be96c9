// Builders of the numerical hard cases (deepgi/hard_cases.hpp).
#include "deepgi/hard_cases.hpp"

#include "deepgi/renderer.hpp"

#include "deepgi/scene_builder.hpp"

#include <algorithm>
#include <cmath>

namespace deepgi::hard_cases {
namespace {

Camera camera_at_origin(float near_plane = 0.05f) {
    Camera camera;
    camera.vertical_fov = glm::radians(60.0f);
    camera.near_plane = near_plane;
    return camera;  // at the origin, looking down -Z
}

// A white quad of half size l in the plane y = height, facing up.
Scene open_floor(const char* name, float height) {
    Scene scene;
    scene.name = name;
    SceneBuilder builder;
    const int white = builder.add_material({0.8f, 0.8f, 0.8f});
    const float l = 1e4f;
    builder.add_quad({-l, height, l}, {l, height, l}, {l, height, -l}, {-l, height, -l}, {0, 1, 0},
                     white);
    builder.finish(scene);
    return scene;
}

void set_camera(Scene& scene, const Camera& camera) {
    scene.default_camera = camera;
    scene.camera_path.keys = {camera};
}

}  // namespace

RenderSettings base_settings(int width, int height) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.shadow_map_size = 64;
    return settings;
}

Scene scaled_scene(Scene scene, float s) {
    for (Vertex& v : scene.vertices) v.position *= s;
    scene.default_camera.position *= s;
    scene.default_camera.near_plane *= s;
    scene.camera_path.keys = {scene.default_camera};
    scene.bounds = compute_bounds(scene.vertices);
    return scene;
}

RenderSettings scaled_settings(RenderSettings settings, float s) {
    settings.ao.radius *= s;
    settings.ao.bias *= s;
    settings.ao.thickness *= s;
    settings.min_separation *= s;
    return settings;
}

Scene far_floor(float pitch_degrees) {
    Scene scene = open_floor("far-floor", 0.0f);
    Camera camera = camera_at_origin(1e-3f);
    camera.pitch = glm::radians(pitch_degrees);
    camera.position.y = 1000.0f * std::sin(glm::radians(-pitch_degrees));
    set_camera(scene, camera);
    return scene;
}

Scene grazing_floor(float pitch_degrees) {
    Scene scene = open_floor("open-floor", -1.0f);
    Camera camera = camera_at_origin();
    camera.pitch = glm::radians(pitch_degrees);
    set_camera(scene, camera);
    return scene;
}

std::vector<int> guard_edge_columns(const RenderSettings& settings) {
    const int guard = frame_layout(settings).guard;
    return {-guard / 2, 0, 1};
}

Scene guard_edge(const RenderSettings& settings, int edge_column) {
    const Camera camera = camera_at_origin();
    const float tan_half = std::tan(camera.vertical_fov * 0.5f);
    const float aspect = float(settings.width) / float(settings.height);
    // The camera-space x at the near wall's depth of the column's centre.
    const float ndc = 2.0f * (float(edge_column) + 0.5f) / float(settings.width) - 1.0f;
    const float near_z = 0.3f, far_z = 50.0f;
    const float edge_x = ndc * tan_half * aspect * near_z;
    Scene scene;
    scene.name = "guard-edge";
    SceneBuilder builder;
    const int white = builder.add_material({0.8f, 0.8f, 0.8f});
    builder.add_quad({-100, -100, -far_z}, {100, -100, -far_z}, {100, 100, -far_z},
                     {-100, 100, -far_z}, {0, 0, 1}, white);
    builder.add_quad({-10, -10, -near_z}, {edge_x, -10, -near_z}, {edge_x, 10, -near_z},
                     {-10, 10, -near_z}, {0, 0, 1}, white);
    builder.finish(scene);
    set_camera(scene, camera);
    return scene;
}

AoFrame render_ao(const Scene& scene, const RenderSettings& settings, const ShaderLoader& loader) {
    Renderer renderer(scene, settings, loader);
    renderer.render(scene.default_camera);
    return {renderer.read_pass_output("depth_pyramid-level0"), renderer.read_pass_output("ao-raw"),
            renderer.read_pass_output("ao-blurred")};
}

double lowest_on_surfaces(const AoFrame& frame, int guard, long long* surface_pixels) {
    *surface_pixels = 0;
    double lowest = 1.0;
    for (int y = guard; y < frame.raw.height - guard; ++y) {
        for (int x = guard; x < frame.raw.width - guard; ++x) {
            if (!(frame.depth.at(x, y, 0) > 0.0f)) continue;
            ++*surface_pixels;
            lowest = std::min({lowest, double(frame.raw.at(x, y)), double(frame.blurred.at(x, y))});
        }
    }
    return lowest;
}

}  // namespace deepgi::hard_cases
