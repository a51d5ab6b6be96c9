// Reflected rays that meet another mirror (docs/reflections.md, "Against the
// ray tracer"): the reference follows them, mirror after mirror, against a
// closed-form oracle. A mirror floor faces a mirror wall, and an emitting
// black box stands behind the camera, where only a ray reflected twice (floor
// then wall, or wall then floor) or once (wall) can reach it. The oracle
// intersects the two axis-aligned rectangles and the box (slabs) along each
// reflected ray and reflects by flipping one coordinate, so every path and
// its radiance, the product of the mirrors' reflectances times the box's
// emission or the environment, is known without the ray tracer.
#include "deepgi/reference.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene_builder.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace {

const glm::vec3 floor_reflectance{0.9f, 0.9f, 0.9f};
const glm::vec3 wall_reflectance{0.5f, 0.8f, 0.7f};
const glm::vec3 box_centre{0.0f, 1.2f, 3.0f}, box_half{2.5f, 1.0f, 0.3f};
const glm::vec3 box_emission{2.0f, 1.0f, 0.5f};
constexpr float wall_z = -4.0f, wall_top = 5.0f, half_width = 6.0f;

deepgi::Scene facing_mirrors_scene() {
    deepgi::SceneBuilder builder;
    const int floor_mirror = builder.add_mirror_material(floor_reflectance);
    const int wall_mirror = builder.add_mirror_material(wall_reflectance);
    const int lamp = builder.add_material({0.0f, 0.0f, 0.0f}, box_emission);
    builder.add_quad({-half_width, 0, -half_width}, {half_width, 0, -half_width},
                     {half_width, 0, half_width}, {-half_width, 0, half_width}, {0, 1, 0},
                     floor_mirror);
    builder.add_quad({-half_width, 0, wall_z}, {half_width, 0, wall_z},
                     {half_width, wall_top, wall_z}, {-half_width, wall_top, wall_z}, {0, 0, 1},
                     wall_mirror);
    builder.add_box(box_centre, box_half, lamp);
    deepgi::Scene scene;
    scene.name = "facing-mirrors";
    builder.finish(scene);
    scene.key_light.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.6f));
    scene.key_light.intensity = 3.0f;
    scene.default_camera.position = {0.0f, 1.0f, 1.0f};
    scene.default_camera.pitch = -0.25f;
    return scene;
}

// The oracle's objects: 0 floor, 1 wall, 2 box, -1 nothing.
struct OracleHit {
    int object = -1;
    float distance = 0.0f;
    float margin = 1e30f;  // distance of the hit point to its object's nearest edge
};

OracleHit oracle_intersect(glm::vec3 o, glm::vec3 u) {
    OracleHit best;
    best.distance = 1e30f;
    auto consider = [&](int object, float s, float margin) {
        if (s > 1e-4f && s < best.distance) best = {object, s, margin};
    };
    if (u.y < 0.0f) {  // the floor y = 0, seen from above
        const float s = -o.y / u.y;
        const glm::vec3 p = o + s * u;
        const float margin = std::min(half_width - std::abs(p.x), half_width - std::abs(p.z));
        if (margin >= 0.0f) consider(0, s, margin);
    }
    if (u.z < 0.0f) {  // the wall z = wall_z, seen from the front
        const float s = (wall_z - o.z) / u.z;
        const glm::vec3 p = o + s * u;
        const float margin = std::min({half_width - std::abs(p.x), p.y, wall_top - p.y});
        if (margin >= 0.0f) consider(1, s, margin);
    }
    // The box by slabs: entry distance, and how far the entry point is from
    // the entered face's edges.
    const glm::vec3 lo = box_centre - box_half, hi = box_centre + box_half;
    float near = 0.0f, far = 1e30f;
    int axis = -1;
    bool parallel_outside = false;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(u[a]) < 1e-12f) {
            parallel_outside |= o[a] < lo[a] || o[a] > hi[a];
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
    if (!parallel_outside && axis >= 0 && near <= far) {
        const glm::vec3 p = o + near * u;
        float margin = 1e30f;
        for (int a = 0; a < 3; ++a)
            if (a != axis) margin = std::min({margin, p[a] - lo[a], hi[a] - p[a]});
        consider(2, near, margin);
    }
    if (best.object < 0) best.distance = 0.0f;
    return best;
}

// The whole path from a mirror point along u: the first object, the radiance
// arriving (before the starting mirror's reflectance, as the reference gives
// it) and the mirrors met, or nullopt when some hit lies within 1 mm of an
// edge.
struct OraclePath {
    OracleHit first;
    glm::vec3 radiance{0.0f};
    int mirror_bounces = 0;
    bool box = false;  // the path ends on the box
};

std::optional<OraclePath> oracle_path(glm::vec3 o, glm::vec3 u, glm::vec3 ambient) {
    OraclePath path;
    glm::vec3 throughput{1.0f};
    for (int segment = 0; segment < 8; ++segment) {
        const OracleHit hit = oracle_intersect(o, u);
        if (hit.object >= 0 && hit.margin < 1e-3f) return std::nullopt;
        if (segment == 0) path.first = hit;
        if (hit.object < 0) {
            path.radiance = throughput * ambient;
            return path;
        }
        if (hit.object == 2) {
            path.radiance = throughput * box_emission;
            path.box = true;
            return path;
        }
        // A mirror met: its reflectance weighs all that follows.
        ++path.mirror_bounces;
        throughput *= hit.object == 0 ? floor_reflectance : wall_reflectance;
        o += hit.distance * u;
        u[hit.object == 0 ? 1 : 2] *= -1.0f;  // reflect: flip the plane's axis
    }
    return std::nullopt;  // not reached in this scene: each ray leaves after two mirrors
}

}  // namespace

TEST_CASE("reference: rays reflected from mirror to mirror reach what the closed form reaches",
          "[reference][reflection]") {
    const deepgi::Scene scene = facing_mirrors_scene();
    deepgi::ReferenceSettings settings;
    settings.render.width = 64;
    settings.render.height = 36;
    settings.render.min_separation = 0.3f;
    settings.ambient_visibility = false;
    settings.irradiance_rays.min_rays = settings.irradiance_rays.max_rays = 64;
    settings.reflections = true;
    settings.threads = 2;
    const deepgi::RayScene rays(scene);
    const auto images = deepgi::render_reference(rays, scene.default_camera, settings);
    REQUIRE(!images.reflection_radiance.pixels.empty());

    const deepgi::Camera& camera = scene.default_camera;
    const glm::mat4 camera_to_world = glm::inverse(deepgi::camera_view_matrix(camera));
    const glm::vec3 eye = glm::vec3(camera_to_world[3]);
    const int w = images.depth_layer0.width, h = images.depth_layer0.height;
    int mirrors = 0, ambiguous = 0;
    int by_bounces[3] = {0, 0, 0};  // compared pixels by mirrors their reflected ray meets
    int reach_box = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * w + x;
            if (images.surface_layers.pixels[3 * i + 2] != 1.0f) continue;
            ++mirrors;
            const float depth = images.depth_layer0.pixels[i];
            const glm::vec3 d = glm::vec3(
                camera_to_world *
                glm::vec4(deepgi::camera_ray_direction(camera, settings.render, x + 0.5f, y + 0.5f),
                          0.0f));
            const glm::vec3 point = eye + d * depth;
            const bool on_floor = std::abs(point.y) < 1e-4f;
            const bool on_wall = std::abs(point.z - wall_z) < 1e-4f;
            REQUIRE((on_floor || on_wall));
            glm::vec3 u = glm::normalize(d);
            u[on_floor ? 1 : 2] *= -1.0f;
            const auto path = oracle_path(point, u, scene.ambient);
            if (!path) {
                ++ambiguous;
                continue;
            }
            ++by_bounces[path->mirror_bounces];
            reach_box += path->box;
            const float traced_surface = images.reflection_hit.pixels[3 * i];
            const float traced_triangle = images.reflection_hit.pixels[3 * i + 1];
            const float traced_distance = images.reflection_hit.pixels[3 * i + 2];
            INFO("pixel " << x << "," << y << " first object " << path->first.object
                          << ", mirrors met " << path->mirror_bounces);
            // The first surface is the oracle's first object, at its distance.
            if (path->first.object < 0) {
                CHECK(traced_surface == -1.0f);
            } else {
                REQUIRE(traced_surface >= 0.0f);
                CHECK(std::abs(traced_distance - path->first.distance) <=
                      2e-4f + 1e-4f * path->first.distance);
                const auto t = std::size_t(traced_triangle);
                const glm::vec3 p0 = scene.vertices[scene.indices[3 * t]].position;
                if (path->first.object == 0) CHECK(std::abs(p0.y) < 1e-5f);
                if (path->first.object == 1) CHECK(std::abs(p0.z - wall_z) < 1e-5f);
            }
            // The radiance: every further mirror's reflectance times the box's
            // emission (black, so nothing else) or the environment.
            for (int c = 0; c < 3; ++c)
                CHECK(images.reflection_radiance.pixels[3 * i + c] ==
                      Approx(path->radiance[c]).epsilon(1e-5));
        }
    INFO("mirror pixels " << mirrors << ", ambiguous " << ambiguous << ", paths meeting 0/1/2 "
                          << "mirrors " << by_bounces[0] << "/" << by_bounces[1] << "/"
                          << by_bounces[2] << ", reaching the box " << reach_box);
    // Both kinds of path are present, in numbers: a reflected ray meets no
    // mirror (the box or the environment) or one (the floor reflects into
    // the wall, the wall into the floor), never two here, since neither
    // reflection turns the ray back towards the mirror it left; the parallel
    // mirrors below make longer chains.
    CHECK(by_bounces[0] >= 100);
    CHECK(by_bounces[1] >= 100);
    CHECK(by_bounces[2] == 0);
    CHECK(reach_box >= 100);
    CHECK(ambiguous * 20 <= mirrors);
}

TEST_CASE("reference: between parallel mirrors the ray stops after the fixed number of mirrors",
          "[reference][reflection]") {
    // A mirror floor under a mirror ceiling, both 200 m wide: a ray leaving
    // the floor upwards bounces between them for ever. The reference follows
    // kMaxMirrorBounces mirrors after the ceiling it meets first and shades
    // the next as diffuse; the first hit is the ceiling at height / cos.
    deepgi::SceneBuilder builder;
    const int floor_mirror = builder.add_mirror_material(floor_reflectance);
    const int ceiling_mirror = builder.add_mirror_material(wall_reflectance);
    const float l = 100.0f, height = 3.0f;
    builder.add_quad({-l, 0, -l}, {l, 0, -l}, {l, 0, l}, {-l, 0, l}, {0, 1, 0}, floor_mirror);
    builder.add_quad({-l, height, l}, {l, height, l}, {l, height, -l}, {-l, height, -l}, {0, -1, 0},
                     ceiling_mirror);
    deepgi::Scene scene;
    builder.finish(scene);
    const deepgi::RayScene rays(scene);
    deepgi::IrradianceRayBudget budget;
    budget.min_rays = budget.max_rays = 64;
    const glm::vec3 eye{0.0f, 1.5f, 0.0f};
    for (const glm::vec3 target : {glm::vec3(0.0f, 0.0f, -2.0f), glm::vec3(1.0f, 0.0f, -5.0f),
                                   glm::vec3(-0.5f, 0.0f, -0.8f)}) {
        const auto sample = deepgi::mirror_reflection_at(rays, eye, target, {0, 1, 0}, {0, 1, 0},
                                                         1.0f, true, budget, 7, 0.1f);
        const glm::vec3 d = glm::normalize(target - eye);
        REQUIRE(sample.hit.hit);
        // The ray leaves the floor by the reference's offset (scene size
        // 200 m, some 2e-4 m), longer along a slanted ray.
        CHECK(sample.hit.distance == Approx(height / -d.y).margin(2e-3));
        CHECK(sample.mirror_bounces == deepgi::kMaxMirrorBounces);
        // Floor and ceiling alternate after the first ceiling: floor, ceiling,
        // floor for three, then the last ceiling shaded as diffuse, lit only
        // by what reaches it (no key light from below, ambient off in E).
        CHECK(std::isfinite(sample.radiance.x));
    }
}
