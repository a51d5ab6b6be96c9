// The traced mirror reflections (docs/reflections.md, "Against the ray
// tracer") against the mirror image of the camera: a ray reflected in the
// floor y = 0 continues the straight line from the camera's image below the
// floor, (x, -y, z), through the mirror point, so where it meets a box
// follows from a ray-box intersection in closed form.
#include "deepgi/reference.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene_builder.hpp"

#include <catch2/catch.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

const glm::vec3 box_centre{0.2f, 0.6f, -2.5f}, box_half{1.0f, 0.6f, 0.4f};
const glm::vec3 box_colour{0.8f, 0.2f, 0.1f};

// A mirror floor 12 m square and one red box; the key light falls towards -z
// so the box's face towards the camera is lit.
deepgi::Scene mirror_box_scene() {
    deepgi::SceneBuilder builder;
    const int mirror = builder.add_mirror_material({0.9f, 0.9f, 0.9f});
    const int red = builder.add_material(box_colour);
    builder.add_quad({-6, 0, -6}, {6, 0, -6}, {6, 0, 6}, {-6, 0, 6}, {0, 1, 0}, mirror);
    builder.add_box(box_centre, box_half, red);
    deepgi::Scene scene;
    scene.name = "mirror-box";
    builder.finish(scene);
    scene.key_light.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.6f));
    scene.key_light.intensity = 3.0f;
    scene.default_camera.position = {0.0f, 0.6f, 1.0f};
    scene.default_camera.pitch = -0.2f;
    return scene;
}

deepgi::ReferenceSettings mirror_settings(int threads) {
    deepgi::ReferenceSettings settings;
    settings.render.width = 64;
    settings.render.height = 36;
    settings.render.min_separation = 0.3f;
    settings.ambient_visibility = false;
    settings.irradiance = false;
    settings.irradiance_rays.min_rays = settings.irradiance_rays.max_rays = 256;
    settings.radiosity_radius = 3.0f;
    settings.reflections = true;
    settings.threads = threads;
    return settings;
}

// The entry distance of the ray o + s u (s > 0) into the box grown by
// `grow` on every side and the axis of the face entered, or s < 0: a miss.
float enter_box(glm::vec3 o, glm::vec3 u, float grow, int& axis) {
    const glm::vec3 lo = box_centre - box_half - grow, hi = box_centre + box_half + grow;
    float near = 0.0f, far = 1e30f;
    axis = -1;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(u[a]) < 1e-12f) {
            if (o[a] < lo[a] || o[a] > hi[a]) return -1.0f;
            continue;
        }
        float t0 = (lo[a] - o[a]) / u[a], t1 = (hi[a] - o[a]) / u[a];
        if (t0 > t1) std::swap(t0, t1);
        if (t0 > near) {
            near = t0;
            axis = a;
        }
        far = std::min(far, t1);
    }
    return near <= far && axis >= 0 ? near : -1.0f;
}

}  // namespace

TEST_CASE("reference: a mirror floor reflects the box where the camera's mirror image sees it",
          "[reference][reflection]") {
    const deepgi::Scene scene = mirror_box_scene();
    const deepgi::ReferenceSettings settings = mirror_settings(2);
    const deepgi::RayScene rays(scene);
    const auto images = deepgi::render_reference(rays, scene.default_camera, settings);
    REQUIRE(images.reflection_radiance.width == images.depth_layer0.width);
    REQUIRE(images.reflection_hit.channels == 3);

    const deepgi::Camera& camera = scene.default_camera;
    const glm::mat4 camera_to_world = glm::inverse(deepgi::camera_view_matrix(camera));
    const glm::vec3 eye = glm::vec3(camera_to_world[3]);
    const glm::vec3 image_eye{eye.x, -eye.y, eye.z};  // the camera mirrored in y = 0
    const int w = images.depth_layer0.width, h = images.depth_layer0.height;
    const glm::vec3 light_to = -scene.key_light.direction;
    int mirrors = 0, box_hits = 0, misses = 0, ambiguous = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * w + x;
            const float depth = images.depth_layer0.pixels[i];
            const glm::vec3 direction = glm::vec3(
                camera_to_world *
                glm::vec4(deepgi::camera_ray_direction(camera, settings.render, x + 0.5f, y + 0.5f),
                          0.0f));
            const glm::vec3 point = eye + direction * depth;
            const bool on_floor = depth > 0.0f && std::abs(point.y) < 1e-4f;
            // The mirror flag is the floor's, and only the floor's.
            REQUIRE((images.surface_layers.pixels[3 * i + 2] == 1.0f) == on_floor);
            if (!on_floor) {
                CHECK(images.reflection_hit.pixels[3 * i] == -2.0f);
                CHECK(images.reflection_radiance.pixels[3 * i] == 0.0f);
                continue;
            }
            ++mirrors;
            const glm::vec3 u = glm::normalize(point - image_eye);
            int axis = -1, axis_in = -1, axis_out = -1;
            const float s = enter_box(point, u, 0.0f, axis);
            // Rays within 0.1 mm of an edge could go either way.
            if ((enter_box(point, u, 1e-4f, axis_out) >= 0.0f) !=
                (enter_box(point, u, -1e-4f, axis_in) >= 0.0f)) {
                ++ambiguous;
                continue;
            }
            const float traced_surface = images.reflection_hit.pixels[3 * i];
            const float traced_triangle = images.reflection_hit.pixels[3 * i + 1];
            const float traced_distance = images.reflection_hit.pixels[3 * i + 2];
            const glm::vec3 radiance{images.reflection_radiance.pixels[3 * i],
                                     images.reflection_radiance.pixels[3 * i + 1],
                                     images.reflection_radiance.pixels[3 * i + 2]};
            if (s < 0.0f) {
                ++misses;
                REQUIRE(traced_surface == -1.0f);
                // A miss sees the environment: the scene's ambient radiance
                // (no background colour).
                CHECK(radiance.x == Approx(scene.ambient.x).epsilon(1e-6));
                CHECK(radiance.z == Approx(scene.ambient.z).epsilon(1e-6));
                continue;
            }
            ++box_hits;
            REQUIRE(traced_surface >= 0.0f);
            CHECK(std::abs(traced_distance - s) <= 2e-4f + 1e-4f * s);
            // The triangle hit lies in the face the closed form enters.
            const auto t = std::size_t(traced_triangle);
            const glm::vec3 p0 = scene.vertices[scene.indices[3 * t]].position;
            const glm::vec3 p1 = scene.vertices[scene.indices[3 * t + 1]].position;
            const glm::vec3 p2 = scene.vertices[scene.indices[3 * t + 2]].position;
            const glm::vec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
            CHECK(std::abs(n[axis]) == Approx(1.0f).margin(1e-5));
            CHECK(n[axis] * u[axis] < 0.0f);
            // L = albedo x (direct cosine / pi x intensity + E / pi), E from
            // the grey floor alone (a convex box sees none of itself), so
            // the channels keep the box's colour ratios; and at least the
            // direct light, which nothing shadows on this face.
            CHECK(radiance.x / radiance.y == Approx(box_colour.x / box_colour.y).epsilon(1e-4));
            CHECK(radiance.z / radiance.y == Approx(box_colour.z / box_colour.y).epsilon(1e-4));
            const float direct = box_colour.x / glm::pi<float>() * scene.key_light.intensity *
                                 std::max(0.0f, glm::dot(n, light_to));
            CHECK(radiance.x >= direct * (1.0f - 1e-5f));
        }
    INFO("mirror pixels " << mirrors << ", box " << box_hits << ", misses " << misses
                          << ", ambiguous " << ambiguous);
    CHECK(box_hits >= 100);
    CHECK(misses >= 100);
    CHECK(ambiguous * 50 <= mirrors);
}

TEST_CASE("reference: reflection images do not depend on the thread count",
          "[reference][reflection]") {
    const deepgi::Scene scene = mirror_box_scene();
    const deepgi::RayScene rays(scene);
    const auto one = deepgi::render_reference(rays, scene.default_camera, mirror_settings(1));
    const auto three = deepgi::render_reference(rays, scene.default_camera, mirror_settings(3));
    REQUIRE(!one.reflection_radiance.pixels.empty());
    CHECK(one.reflection_radiance.pixels == three.reflection_radiance.pixels);
    CHECK(one.reflection_hit.pixels == three.reflection_hit.pixels);
    CHECK(one.surface_layers.pixels == three.surface_layers.pixels);
}

TEST_CASE("reference: scenes without mirrors trace no reflections and keep their images",
          "[reference][reflection]") {
    deepgi::ReferenceSettings on = mirror_settings(2);
    on.ambient_visibility = true;
    on.irradiance = true;
    on.rays.min_rays = on.rays.max_rays = 256;
    on.render.ao.radius = 0.5f;
    deepgi::ReferenceSettings off = on;
    off.reflections = false;
    const deepgi::Scene scene = deepgi::make_builtin_scene("ref-slab");
    const deepgi::RayScene rays(scene);
    REQUIRE_FALSE(rays.has_mirrors(on.render.mirror_roughness));
    const auto with = deepgi::render_reference(rays, scene.default_camera, on);
    const auto without = deepgi::render_reference(rays, scene.default_camera, off);
    CHECK(with.reflection_radiance.pixels.empty());
    CHECK(with.reflection_hit.pixels.empty());
    CHECK(with.surface_layers.pixels.empty());
    CHECK(with.depth_layer0.pixels == without.depth_layer0.pixels);
    CHECK(with.depth_layer1.pixels == without.depth_layer1.pixels);
    CHECK(with.ambient_visibility.pixels == without.ambient_visibility.pixels);
    CHECK(with.occlusion_split.pixels == without.occlusion_split.pixels);
    CHECK(with.irradiance.pixels == without.irradiance.pixels);
    CHECK(with.direct_radiance.pixels == without.direct_radiance.pixels);

    // A mirror scene under a threshold its mirror does not meet has none.
    const deepgi::Scene box = mirror_box_scene();
    const deepgi::RayScene box_rays(box);
    deepgi::ReferenceSettings strict = mirror_settings(2);
    strict.render.mirror_roughness = -1.0f;
    CHECK(deepgi::render_reference(box_rays, box.default_camera, strict)
              .reflection_radiance.pixels.empty());
}

TEST_CASE("reference: deepgi reference writes reflection images for mirrors only",
          "[reference][reflection]") {
    namespace fs = std::filesystem;
    const fs::path root = fs::temp_directory_path() / "deepgi_reference_reflection_cli_test";
    fs::remove_all(root);
    fs::create_directories(root);
    const std::string common = std::string(DEEPGI_EXECUTABLE) +
                               " reference --size 16x9 --no-ao --irradiance-rays 256 "
                               "--irradiance-min-rays 256 --threads 2 --output ";
    REQUIRE(std::system(
                (common + (root / "slab").string() + " --scene ref-slab > /dev/null").c_str()) ==
            0);
    REQUIRE(std::system(
                (common + (root / "gallery").string() + " --scene gallery > /dev/null").c_str()) ==
            0);
    for (const auto& entry : fs::directory_iterator(root / "slab")) {
        const std::string name = entry.path().filename().string();
        CHECK(name.find("reflection") == std::string::npos);
        CHECK(name.find("surface") == std::string::npos);
    }
    for (const char* name :
         {"reference-reflection-radiance", "reference-reflection-hit", "reference-surface-layers"})
        for (const char* extension : {".pfm", ".png"})
            CHECK(fs::exists(root / "gallery" / (std::string(name) + extension)));
    const auto hit = deepgi::read_pfm(root / "gallery" / "reference-reflection-hit.pfm");
    const auto layers = deepgi::read_pfm(root / "gallery" / "reference-surface-layers.pfm");
    int mirrors = 0;
    for (std::size_t i = 0; i < layers.pixels.size() / 3; ++i)
        if (layers.pixels[3 * i + 2] == 1.0f) {
            ++mirrors;
            CHECK(hit.pixels[3 * i] >= -1.0f);
        } else {
            CHECK(hit.pixels[3 * i] == -2.0f);
        }
    CHECK(mirrors > 0);
    // --no-reflections writes the set of a scene without mirrors.
    REQUIRE(std::system(
                (common + (root / "off").string() + " --scene gallery --no-reflections > /dev/null")
                    .c_str()) == 0);
    CHECK_FALSE(fs::exists(root / "off" / "reference-reflection-radiance.pfm"));
    fs::remove_all(root);
}
