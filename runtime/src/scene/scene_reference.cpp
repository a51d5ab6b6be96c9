// Small scenes for measuring deep SAO against the ray-traced reference, each
// built around one way screen-space AO can err: a crease with a closed form,
// a slab above a floor, a thin board in front of a wall, and a bench behind a
// row of posts (occluders only layer 1 sees); and, for the mirror
// reflections, a room whose mirror floor meets a mirror wall, where reflected
// rays meet a second mirror. Grey Lambertian surfaces (and the two mirrors)
// under one directional light.
#include "deepgi/errors.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/scene_builder.hpp"

#include <fmt/format.h>
#include <glm/gtc/constants.hpp>

namespace deepgi {
namespace {

Camera look(glm::vec3 position, float yaw_degrees, float pitch_degrees) {
    Camera camera;
    camera.position = position;
    camera.yaw = glm::radians(yaw_degrees);
    camera.pitch = glm::radians(pitch_degrees);
    camera.vertical_fov = glm::radians(50.0f);
    return camera;
}

// Floor y = 0 over [-l, l]^2.
void add_floor(SceneBuilder& builder, float l, int material) {
    builder.add_quad({-l, 0, -l}, {l, 0, -l}, {l, 0, l}, {-l, 0, l}, {0, 1, 0}, material);
}

Scene finish(SceneBuilder& builder, std::string name, Camera camera) {
    Scene scene;
    scene.name = std::move(name);
    builder.finish(scene);
    scene.key_light.kind = LightKind::directional;
    scene.key_light.direction = glm::normalize(glm::vec3(0.4f, -1.0f, -0.3f));
    scene.key_light.intensity = 3.0f;
    scene.ambient = glm::vec3(0.05f);
    scene.background = glm::vec3(0.2f, 0.25f, 0.3f);
    scene.default_camera = camera;
    scene.camera_path.keys = {camera};
    return scene;
}

}  // namespace

std::vector<std::string> reference_scene_names() {
    return {"ref-crease", "ref-slab", "ref-board", "ref-bench", "ref-mirrors"};
}

Scene make_reference_scene(std::string_view name) {
    SceneBuilder builder;
    const int grey = builder.add_material({0.6f, 0.6f, 0.6f});
    if (name == "ref-crease") {
        // Floor meeting a wall at z = -2 at a right angle: along the floor the
        // reference has the closed form of the inside corner.
        add_floor(builder, 20.0f, grey);
        builder.add_quad({-20, 0, -2}, {20, 0, -2}, {20, 6, -2}, {-20, 6, -2}, {0, 0, 1}, grey);
        return finish(builder, std::string(name), look({0.6f, 1.3f, 1.2f}, 10.0f, -30.0f));
    }
    if (name == "ref-slab") {
        // A 1.2 m slab, 6 cm thick, 25 cm above the floor.
        add_floor(builder, 20.0f, grey);
        builder.add_box({0.0f, 0.28f, -1.5f}, {0.6f, 0.03f, 0.6f}, grey, glm::radians(20.0f));
        return finish(builder, std::string(name), look({0.3f, 1.4f, 0.6f}, 5.0f, -35.0f));
    }
    if (name == "ref-board") {
        // A 2 cm board standing 15 cm in front of a wall, seen at an angle.
        add_floor(builder, 20.0f, grey);
        builder.add_quad({-20, 0, -3}, {20, 0, -3}, {20, 6, -3}, {-20, 6, -3}, {0, 0, 1}, grey);
        builder.add_box({0.0f, 0.9f, -2.84f}, {0.5f, 0.6f, 0.01f}, grey);
        return finish(builder, std::string(name), look({1.2f, 1.2f, 0.2f}, 20.0f, -8.0f));
    }
    if (name == "ref-bench") {
        // A bench 0.45 m high behind a row of posts 0.9 m nearer the camera:
        // parts of the bench that occlude the floor are hidden behind the
        // posts, so only layer 1 sees them.
        add_floor(builder, 20.0f, grey);
        builder.add_box({0.0f, 0.45f, -3.0f}, {1.2f, 0.03f, 0.25f}, grey);    // seat
        builder.add_box({-1.1f, 0.21f, -3.0f}, {0.04f, 0.21f, 0.22f}, grey);  // legs
        builder.add_box({1.1f, 0.21f, -3.0f}, {0.04f, 0.21f, 0.22f}, grey);
        for (int i = -3; i <= 3; ++i)
            builder.add_box({0.32f * float(i), 0.7f, -2.1f}, {0.07f, 0.7f, 0.07f}, grey);
        return finish(builder, std::string(name), look({0.1f, 0.9f, 0.2f}, 0.0f, -14.0f));
    }
    if (name == "ref-mirrors") {
        // A mirror floor meeting a mirror wall on the left (x = -3) at a
        // right angle, in a room open towards the camera: rays leaving the
        // floor towards the wall are reflected again, on to the grey back
        // wall, the coloured right wall and the two boxes, which the camera
        // sees, so a screen-space march can find where they end.
        const int mirror = builder.add_mirror_material({0.9f, 0.9f, 0.9f});
        const int warm = builder.add_material({0.75f, 0.55f, 0.35f});
        const int red = builder.add_material({0.8f, 0.1f, 0.08f});
        const int green = builder.add_material({0.1f, 0.7f, 0.2f});
        const float half = 3.0f, back = -5.0f, front = 4.0f, height = 3.0f;
        builder.add_quad({-half, 0, back}, {half, 0, back}, {half, 0, front}, {-half, 0, front},
                         {0, 1, 0}, mirror);
        builder.add_quad({-half, 0, back}, {-half, 0, front}, {-half, height, front},
                         {-half, height, back}, {1, 0, 0}, mirror);
        builder.add_quad({-half, 0, back}, {half, 0, back}, {half, height, back},
                         {-half, height, back}, {0, 0, 1}, grey);
        builder.add_quad({half, 0, back}, {half, 0, front}, {half, height, front},
                         {half, height, back}, {-1, 0, 0}, warm);
        builder.add_box({-0.6f, 0.45f, -2.6f}, {0.45f, 0.45f, 0.45f}, red, glm::radians(25.0f));
        builder.add_box({1.3f, 0.6f, -1.2f}, {0.3f, 0.6f, 0.3f}, green);
        return finish(builder, std::string(name), look({1.8f, 1.9f, 3.8f}, -28.0f, -20.0f));
    }
    throw InputError(fmt::format("unknown reference scene '{}'", name));
}

}  // namespace deepgi
