// Camera paths of the built-in scenes: every camera along the path stands
// inside the scene's bounds (the oracle: the box around its vertices,
// computed in the test), and from inside cornell's room (a closed room
// but for its open side, which the path faces away from) every pixel of
// layer 0 hits a surface: the path never shows the void around the box.
#include "deepgi/context.hpp"
#include "deepgi/renderer.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

using namespace deepgi;

namespace {

// The box around every vertex, computed here.
Bounds vertex_box(const Scene& scene) {
    Bounds box{scene.vertices.front().position, scene.vertices.front().position};
    for (const Vertex& vertex : scene.vertices) {
        box.min = glm::min(box.min, vertex.position);
        box.max = glm::max(box.max, vertex.position);
    }
    return box;
}

bool inside(const Bounds& bounds, glm::vec3 point, float margin) {
    return glm::all(glm::greaterThanEqual(point, bounds.min + margin)) &&
           glm::all(glm::lessThanEqual(point, bounds.max - margin));
}

}  // namespace

TEST_CASE("camera path: every camera of every built-in scene's path is inside the scene's bounds",
          "[runtime][camera_path]") {
    for (const std::string& name : builtin_scene_names()) {
        const Scene scene = make_builtin_scene(name);
        const Bounds bounds = vertex_box(scene);
        const int cycle = int(scene.camera_path.keys.size()) * scene.camera_path.frames_per_key;
        REQUIRE(cycle > 1);
        // Two whole loops, and frames before the first (the path is periodic).
        for (int frame = -cycle; frame <= 2 * cycle; ++frame) {
            const Camera camera = camera_on_path(scene.camera_path, frame);
            INFO(name << " frame " << frame << ": camera at " << camera.position.x << ", "
                      << camera.position.y << ", " << camera.position.z);
            // At least the near plane from every side of the box.
            REQUIRE(inside(bounds, camera.position, camera.near_plane));
        }
    }
}

TEST_CASE("camera path: along cornell's path layer 0 hits a surface at every pixel",
          "[runtime][camera_path]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    RenderSettings settings;
    settings.width = 64;
    settings.height = 36;
    settings.shadow_map_size = 64;
    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
    const int guard = renderer.layout().guard;
    const int cycle = int(scene.camera_path.keys.size()) * scene.camera_path.frames_per_key;
    for (int frame = 0; frame < cycle; frame += 4) {
        renderer.render(camera_on_path(scene.camera_path, frame), CameraMotion::cut);
        const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
        int empty = 0;
        for (int y = guard; y < guard + settings.height; ++y)
            for (int x = guard; x < guard + settings.width; ++x) empty += depth.at(x, y, 0) <= 0.0f;
        INFO("cornell path frame " << frame << ": " << empty << " viewport pixels show nothing");
        CHECK(empty == 0);
    }
}
