// The built-in procedural scenes. Each is chosen to give the second G-buffer
// layer something to do: surfaces hidden behind blocks, columns and shelves.
#include "deepgi/errors.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/scene_builder.hpp"

#include <fmt/format.h>

#include <cstdint>

namespace deepgi {

namespace {

Camera make_camera(glm::vec3 position, float yaw_degrees, float pitch_degrees, float fov_degrees) {
    Camera camera;
    camera.position = position;
    camera.yaw = glm::radians(yaw_degrees);
    camera.pitch = glm::radians(pitch_degrees);
    camera.vertical_fov = glm::radians(fov_degrees);
    return camera;
}

Scene make_cornell() {
    Scene scene;
    scene.name = "cornell";
    SceneBuilder builder;
    const int white = builder.add_material({0.73f, 0.73f, 0.73f});
    const int red = builder.add_material({0.63f, 0.065f, 0.05f});
    const int green = builder.add_material({0.14f, 0.45f, 0.091f});
    const int lamp = builder.add_material({0.78f, 0.78f, 0.78f}, {12.0f, 10.0f, 7.0f});
    // Room: x in [-1, 1], y in [0, 2], z in [-1, 1], open towards +z.
    builder.add_quad({-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}, {0, 1, 0}, white);   // floor
    builder.add_quad({-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}, {0, -1, 0}, white);  // ceiling
    builder.add_quad({-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1}, {0, 0, 1}, white);  // back
    builder.add_quad({-1, 0, -1}, {-1, 0, 1}, {-1, 2, 1}, {-1, 2, -1}, {1, 0, 0}, red);    // left
    builder.add_quad({1, 0, -1}, {1, 0, 1}, {1, 2, 1}, {1, 2, -1}, {-1, 0, 0}, green);     // right
    builder.add_quad({-0.25f, 1.995f, -0.2f}, {0.25f, 1.995f, -0.2f}, {0.25f, 1.995f, 0.2f},
                     {-0.25f, 1.995f, 0.2f}, {0, -1, 0}, lamp);
    builder.add_box({-0.33f, 0.6f, -0.35f}, {0.28f, 0.6f, 0.28f}, white,
                    glm::radians(17.0f));  // tall block
    builder.add_box({0.35f, 0.3f, 0.3f}, {0.28f, 0.3f, 0.28f}, white,
                    glm::radians(-17.0f));  // short block
    builder.finish(scene);

    scene.key_light.kind = LightKind::spot;
    scene.key_light.position = {0.0f, 1.97f, 0.0f};
    scene.key_light.direction = {0.0f, -1.0f, 0.0f};
    scene.key_light.colour = {1.0f, 0.9f, 0.75f};
    scene.key_light.intensity = 12.0f;
    scene.key_light.outer_cone = glm::radians(70.0f);
    scene.key_light.inner_cone = glm::radians(40.0f);
    scene.ambient = glm::vec3(0.04f);
    scene.background = glm::vec3(0.0f);
    scene.default_camera = make_camera({0.0f, 1.0f, 3.6f}, 0.0f, 0.0f, 40.0f);
    // The path stays inside the room, just behind its open side, with a
    // wider lens: from outside (where the default camera stands) a turn of
    // the head shows the void beside the box. The room is convex and the
    // keys are above the short block and in front of both blocks, so every
    // point between two keys is inside it too (camera_path_test.cpp).
    scene.camera_path.frames_per_key = 24;
    scene.camera_path.keys = {
        make_camera({0.0f, 1.0f, 0.95f}, 0.0f, 0.0f, 65.0f),
        make_camera({-0.55f, 1.25f, 0.9f}, -12.0f, -6.0f, 65.0f),
        make_camera({0.5f, 0.8f, 0.9f}, 14.0f, 3.0f, 65.0f),
    };
    return scene;
}

// A colonnade around a courtyard: columns on a square, stepped arches between
// them, a roofed gallery behind, and saturated banners hanging in the gallery
// directly behind the columns, so layer 1 sees what layer 0's columns hide.
Scene make_atrium() {
    Scene scene;
    scene.name = "atrium";
    SceneBuilder builder;
    const int stone = builder.add_material({0.62f, 0.58f, 0.52f});
    const int plaster = builder.add_material({0.78f, 0.74f, 0.66f});
    const int column_stone = builder.add_material({0.70f, 0.68f, 0.64f});
    const glm::vec3 banner_colours[] = {{0.80f, 0.04f, 0.04f},
                                        {0.05f, 0.12f, 0.80f},
                                        {0.85f, 0.68f, 0.04f},
                                        {0.05f, 0.70f, 0.15f},
                                        {0.72f, 0.05f, 0.62f}};
    int banners[5];
    for (int i = 0; i < 5; ++i) banners[i] = builder.add_material(banner_colours[i]);

    const float wall = 9.5f;     // gallery back walls
    const float columns = 6.0f;  // column line
    const float roof = 5.0f;
    builder.add_quad({-wall, 0, -wall}, {wall, 0, -wall}, {wall, 0, wall}, {-wall, 0, wall},
                     {0, 1, 0}, stone);
    builder.add_box({0.0f, 0.25f, 0.0f}, {0.9f, 0.25f, 0.9f}, column_stone);  // fountain basin

    // The four sides share one layout, rotated: `side` maps (along, across) to x/z.
    for (int side = 0; side < 4; ++side) {
        auto at = [side](float along, float y, float across) {
            switch (side) {
                case 0:
                    return glm::vec3(along, y, -across);
                case 1:
                    return glm::vec3(across, y, along);
                case 2:
                    return glm::vec3(-along, y, across);
                default:
                    return glm::vec3(-across, y, -along);
            }
        };
        const glm::vec3 inward = glm::normalize(at(0, 0, -1) - at(0, 0, 0));
        const float yaw = glm::radians(90.0f * float(side));
        builder.add_quad(at(-wall, 0, wall), at(wall, 0, wall), at(wall, roof, wall),
                         at(-wall, roof, wall), inward, plaster);
        builder.add_quad(at(-wall, roof, columns - 0.3f), at(wall, roof, columns - 0.3f),
                         at(wall, roof, wall), at(-wall, roof, wall), {0, -1, 0}, plaster);
        // Beam over the columns.
        builder.add_box(at(0.0f, 4.5f, columns), {6.3f, 0.5f, 0.3f}, column_stone, yaw);
        for (int step = -3; step < 3; ++step) {  // corners belong to the next side
            const float along = 2.0f * float(step);
            builder.add_box(at(along, 2.0f, columns), {0.3f, 2.0f, 0.3f}, column_stone, yaw);
            // Stepped haunches on both sides of each column make the openings arches.
            for (float direction : {-1.0f, 1.0f}) {
                builder.add_box(at(along + direction * 0.5f, 3.75f, columns), {0.2f, 0.25f, 0.28f},
                                column_stone, yaw);
                builder.add_box(at(along + direction * 0.75f, 3.9f, columns), {0.15f, 0.1f, 0.28f},
                                column_stone, yaw);
            }
            if (step > -3) {
                const int banner = banners[(side * 5 + step + 3) % 5];
                builder.add_box(at(along, 3.05f, columns + 1.3f), {0.55f, 1.55f, 0.03f}, banner,
                                yaw);
            }
        }
    }
    builder.finish(scene);

    scene.key_light.kind = LightKind::directional;
    scene.key_light.direction = glm::normalize(
        glm::vec3(0.3f, -0.6f,
                  -0.75f));  // from behind the default camera, low enough to reach into the gallery
    scene.key_light.colour = {1.0f, 0.95f, 0.85f};
    scene.key_light.intensity = 4.0f;
    scene.ambient = {0.07f, 0.08f, 0.10f};
    scene.background = {0.45f, 0.6f, 0.9f};
    scene.default_camera = make_camera({0.0f, 1.7f, 3.0f}, 0.0f, 4.0f, 60.0f);
    scene.camera_path.frames_per_key = 30;
    scene.camera_path.keys = {
        scene.default_camera,
        make_camera({-3.0f, 1.7f, 1.0f}, -30.0f, 3.0f, 60.0f),
        make_camera({-3.5f, 1.8f, -2.0f}, -70.0f, 2.0f, 60.0f),
        make_camera({2.0f, 1.6f, -1.0f}, 40.0f, 5.0f, 60.0f),
    };
    return scene;
}

// Deterministic pseudo-random numbers for carton sizes (same scene every run).
struct CartonRandom {
    std::uint32_t state = 12345u;
    float next() {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / float(1u << 24);
    }
};

// Aisles of shelves under a roof with skylight strips: many surfaces behind
// each other along every view ray.
Scene make_warehouse() {
    Scene scene;
    scene.name = "warehouse";
    SceneBuilder builder;
    const int concrete = builder.add_material({0.45f, 0.45f, 0.43f});
    const int wall_paint = builder.add_material({0.60f, 0.60f, 0.62f});
    const int roof_material = builder.add_material({0.50f, 0.50f, 0.50f});
    const int steel = builder.add_material({0.20f, 0.30f, 0.55f});
    const int plank = builder.add_material({0.80f, 0.45f, 0.10f});
    const int cardboard[3] = {builder.add_material({0.55f, 0.40f, 0.25f}),
                              builder.add_material({0.65f, 0.52f, 0.33f}),
                              builder.add_material({0.75f, 0.75f, 0.72f})};
    const int exit_sign = builder.add_material({0.1f, 0.6f, 0.2f}, {0.3f, 4.0f, 0.8f});

    const float half_x = 15.0f;
    const float half_z = 20.0f;
    const float height = 8.0f;
    builder.add_quad({-half_x, 0, -half_z}, {half_x, 0, -half_z}, {half_x, 0, half_z},
                     {-half_x, 0, half_z}, {0, 1, 0}, concrete);
    builder.add_quad({-half_x, 0, -half_z}, {half_x, 0, -half_z}, {half_x, height, -half_z},
                     {-half_x, height, -half_z}, {0, 0, 1}, wall_paint);
    builder.add_quad({-half_x, 0, half_z}, {half_x, 0, half_z}, {half_x, height, half_z},
                     {-half_x, height, half_z}, {0, 0, -1}, wall_paint);
    builder.add_quad({-half_x, 0, -half_z}, {-half_x, 0, half_z}, {-half_x, height, half_z},
                     {-half_x, height, -half_z}, {1, 0, 0}, wall_paint);
    builder.add_quad({half_x, 0, -half_z}, {half_x, 0, half_z}, {half_x, height, half_z},
                     {half_x, height, -half_z}, {-1, 0, 0}, wall_paint);
    builder.add_quad({-1.0f, 3.0f, -half_z + 0.01f}, {1.0f, 3.0f, -half_z + 0.01f},
                     {1.0f, 3.5f, -half_z + 0.01f}, {-1.0f, 3.5f, -half_z + 0.01f}, {0, 0, 1},
                     exit_sign);
    // Roof strips running along x, with 1.5 m skylight gaps between them.
    for (float z = -half_z; z < half_z - 0.01f; z += 5.0f) {
        builder.add_quad({-half_x, height, z}, {half_x, height, z}, {half_x, height, z + 3.5f},
                         {-half_x, height, z + 3.5f}, {0, -1, 0}, roof_material);
    }

    CartonRandom random;
    const float shelf_rows_x[] = {-11.0f, -7.0f, -3.0f, 1.0f, 5.0f, 9.0f};
    const float bay = 2.5f;
    const float shelf_levels[] = {0.15f, 1.6f, 3.05f, 4.5f};
    for (float row_x : shelf_rows_x) {
        for (float z = -15.0f; z < 15.0f - 0.01f; z += bay) {
            for (float dx : {-0.55f, 0.55f}) {
                builder.add_box({row_x + dx, 2.5f, z}, {0.05f, 2.5f, 0.05f}, steel);
            }
            for (float level : shelf_levels) {
                builder.add_box({row_x, level, z + bay * 0.5f}, {0.57f, 0.03f, bay * 0.5f},
                                plank);  // inside the uprights: no coplanar faces
                // Up to three cartons per bay and level, of varied size.
                float cursor = z + 0.15f;
                while (cursor < z + bay - 0.5f) {
                    const float width = 0.35f + 0.45f * random.next();
                    const float box_height = 0.3f + 0.7f * random.next();
                    const float depth = 0.4f + 0.6f * random.next();
                    if (random.next() < 0.8f && cursor + width < z + bay - 0.1f) {
                        builder.add_box(
                            {row_x, level + 0.03f + box_height * 0.5f, cursor + width * 0.5f},
                            {depth * 0.5f, box_height * 0.5f, width * 0.5f},
                            cardboard[static_cast<int>(random.next() * 2.999f)]);
                    }
                    cursor += width + 0.1f;
                }
            }
        }
        builder.add_box({row_x + 0.55f, 2.5f, 15.0f}, {0.05f, 2.5f, 0.05f}, steel);
        builder.add_box({row_x - 0.55f, 2.5f, 15.0f}, {0.05f, 2.5f, 0.05f}, steel);
    }
    builder.finish(scene);

    scene.key_light.kind = LightKind::directional;
    scene.key_light.direction = glm::normalize(glm::vec3(0.25f, -0.9f, 0.2f));
    scene.key_light.colour = {1.0f, 0.96f, 0.9f};
    scene.key_light.intensity = 6.0f;
    scene.ambient = {0.05f, 0.05f, 0.055f};
    scene.background = {0.3f, 0.35f, 0.4f};
    scene.default_camera = make_camera({-0.8f, 1.7f, 17.0f}, -12.0f, -2.0f, 60.0f);
    scene.camera_path.frames_per_key = 30;
    scene.camera_path.keys = {
        scene.default_camera,
        make_camera({-1.0f, 1.8f, 8.0f}, 10.0f, 0.0f, 60.0f),
        make_camera({3.0f, 2.2f, 0.0f}, 35.0f, 4.0f, 60.0f),
        make_camera({-1.0f, 1.6f, 10.0f}, -25.0f, -3.0f, 60.0f),
    };
    return scene;
}

// A room with a mirror floor (docs/reflections.md). A wide pillar hangs from
// a beam and stops 1.1 m above the floor; a green sculpture stands on a
// pedestal 1.5 m behind it, at the pillar's height. From the camera the
// pillar hides the sculpture, so only layer 1 stores it; the mirror's
// reflected rays pass under the pillar and reach it, so it shows in the
// reflection with two layers and not with one. A red box stands in the open
// for the reflection of a plainly visible object.
Scene make_gallery() {
    Scene scene;
    scene.name = "gallery";
    SceneBuilder builder;
    const int mirror = builder.add_mirror_material({0.9f, 0.9f, 0.9f});
    const int plaster = builder.add_material({0.75f, 0.72f, 0.66f});
    const int blue_wall = builder.add_material({0.30f, 0.36f, 0.62f});
    const int warm_wall = builder.add_material({0.72f, 0.58f, 0.40f});
    const int stone = builder.add_material({0.60f, 0.60f, 0.58f});
    const int red = builder.add_material({0.80f, 0.06f, 0.05f});
    const int green = builder.add_material({0.08f, 0.78f, 0.18f});
    const float half_x = 4.0f, back = -6.0f, front = 3.0f, height = 3.4f;
    builder.add_quad({-half_x, 0, back}, {half_x, 0, back}, {half_x, 0, front}, {-half_x, 0, front},
                     {0, 1, 0}, mirror);
    builder.add_quad({-half_x, 0, back}, {half_x, 0, back}, {half_x, height, back},
                     {-half_x, height, back}, {0, 0, 1}, plaster);
    builder.add_quad({-half_x, 0, back}, {-half_x, 0, front}, {-half_x, height, front},
                     {-half_x, height, back}, {1, 0, 0}, blue_wall);
    builder.add_quad({half_x, 0, back}, {half_x, 0, front}, {half_x, height, front},
                     {half_x, height, back}, {-1, 0, 0}, warm_wall);
    // The beam, the hanging pillar (1.1 m to 3.2 m) and the hidden sculpture.
    builder.add_box({0.0f, 3.25f, -1.0f}, {half_x, 0.12f, 0.15f}, stone);
    builder.add_box({0.0f, 2.15f, -1.0f}, {1.2f, 1.05f, 0.12f}, stone);
    builder.add_box({0.0f, 0.95f, -2.5f}, {0.08f, 0.95f, 0.08f}, stone);  // pedestal
    builder.add_box({0.0f, 2.1f, -2.5f}, {0.3f, 0.2f, 0.2f}, green);
    // In the open: a red box, and a full-height pillar at the side.
    builder.add_box({-2.0f, 0.45f, -2.2f}, {0.45f, 0.45f, 0.45f}, red, glm::radians(20.0f));
    builder.add_box({2.6f, height * 0.5f, -3.2f}, {0.3f, height * 0.5f, 0.3f}, stone);
    builder.finish(scene);

    scene.key_light.kind = LightKind::directional;
    scene.key_light.direction = glm::normalize(glm::vec3(0.25f, -0.8f, -0.55f));
    scene.key_light.intensity = 3.0f;
    scene.ambient = glm::vec3(0.05f);
    scene.background = glm::vec3(0.0f);
    scene.default_camera = make_camera({0.0f, 1.7f, 2.0f}, 0.0f, -20.0f, 60.0f);
    scene.camera_path.frames_per_key = 24;
    scene.camera_path.keys = {
        scene.default_camera,
        make_camera({-0.8f, 1.6f, 2.2f}, -8.0f, -18.0f, 60.0f),
        make_camera({0.7f, 1.8f, 1.8f}, 9.0f, -22.0f, 60.0f),
    };
    return scene;
}

}  // namespace

std::vector<std::string> builtin_scene_names() {
    return {"cornell", "atrium", "warehouse", "gallery"};
}

Scene make_builtin_scene(std::string_view name) {
    if (name == "cornell") return make_cornell();
    if (name == "atrium") return make_atrium();
    if (name == "warehouse") return make_warehouse();
    if (name == "gallery") return make_gallery();
    if (name.substr(0, 4) == "ref-") return make_reference_scene(name);
    throw InputError(
        fmt::format("unknown scene '{}' (built-in scenes: cornell, atrium, warehouse, gallery; or "
                    "a .gltf/.glb file)",
                    name));
}

}  // namespace deepgi
