// The ray-traced reference against closed forms: an open plane, the inside
// corner of two planes, and the camera rays against analytic plane depths.
#include "deepgi/reference.hpp"

#include <catch2/catch.hpp>
#include <glm/gtc/constants.hpp>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

// One quad p0 p1 p2 p3, counter-clockwise seen from the side it faces.
void add_quad(deepgi::Scene& scene, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3) {
    const auto base = std::uint32_t(scene.vertices.size());
    const glm::vec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    for (glm::vec3 p : {p0, p1, p2, p3}) scene.vertices.push_back({p, n, {0, 0}});
    for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) scene.indices.push_back(base + i);
}

// The floor y = 0, facing +y, L metres each way.
void add_floor(deepgi::Scene& scene, float l) {
    add_quad(scene, {-l, 0, l}, {l, 0, l}, {l, 0, -l}, {-l, 0, -l});
}

deepgi::ReferenceSettings small_settings(int width, int height) {
    deepgi::ReferenceSettings settings;
    settings.render.width = width;
    settings.render.height = height;
    settings.render.ao.radius = 0.5f;
    settings.rays.min_rays = settings.rays.max_rays = 256;
    settings.threads = 2;
    return settings;
}

}  // namespace

TEST_CASE("reference: an unoccluded plane has visibility 1 head-on and at a grazing angle",
          "[reference]") {
    deepgi::Scene scene;
    add_floor(scene, 1000.0f);
    const deepgi::RayScene rays(scene);
    // Head-on (looking straight down) and grazing (5 degrees below the horizon).
    for (float pitch : {-glm::half_pi<float>() + 1e-3f, glm::radians(-5.0f)}) {
        deepgi::Camera camera;
        camera.position = {0.3f, pitch < -1.0f ? 2.0f : 0.25f, 0.7f};
        camera.pitch = pitch;
        camera.yaw = 0.4f;
        const auto settings = small_settings(40, 30);
        const deepgi::ReferenceImages images = deepgi::render_reference(rays, camera, settings);
        const glm::mat4 to_world = glm::inverse(deepgi::camera_view_matrix(camera));
        int surface = 0;
        for (int y = 0; y < images.ambient_visibility.height; ++y) {
            for (int x = 0; x < images.ambient_visibility.width; ++x) {
                // Independent oracle for the camera ray: where the pixel-centre
                // ray of unit depth meets y = 0, in closed form.
                const glm::vec3 d =
                    glm::vec3(to_world * glm::vec4(deepgi::camera_ray_direction(
                                                       camera, settings.render, x + 0.5f, y + 0.5f),
                                                   0.0f));
                const float depth = d.y < 0.0f ? -camera.position.y / d.y : 0.0f;
                const float got = images.depth_layer0.at(x, y);
                if (depth <= 0.0f || depth > 1500.0f) continue;
                if (glm::length(camera.position + d * depth) > 999.0f) continue;
                ++surface;
                REQUIRE(got == Approx(depth).epsilon(1e-5));
                REQUIRE(images.ambient_visibility.at(x, y) == 1.0f);
                REQUIRE(images.hit_visibility.at(x, y) == 1.0f);
            }
        }
        REQUIRE(surface > 100);
    }
}

// Inside corner: floor y = 0 (normal +y) and an infinite wall x = 0 (normal
// +x); X on the floor at distance x from the wall, a = x / r. Cosine-weighted
// directions are uniform on the unit disk (u, v) = (sin t cos p, sin t sin p)
// with u towards the wall. The ray reaches the wall at distance d = x / u, so
// it hits within r iff u >= a, and with the falloff f = 1 - d^2/r^2 = 1 - a^2/u^2:
//   hit occlusion  = (1/pi) * area{u >= a}        = (acos a - a sqrt(1 - a^2)) / pi
//   occlusion      = (1/pi) * int_a^1 2 sqrt(1-u^2) (1 - a^2/u^2) du
// and with int 2 sqrt(1-u^2)/u^2 du = -2 sqrt(1-u^2)/u - 2 asin u,
//   int_a^1 2 sqrt(1-u^2)/u^2 du = 2 sqrt(1-a^2)/a - 2 acos a, so
//   occlusion      = ((1 + 2a^2) acos a - 3a sqrt(1 - a^2)) / pi.
TEST_CASE("reference: the inside corner of two planes matches the closed-form integral",
          "[reference]") {
    deepgi::Scene scene;
    const float l = 200.0f;
    add_floor(scene, l);
    add_quad(scene, {0, 0, l}, {0, 0, -l}, {0, l, -l}, {0, l, l});  // wall x = 0, facing +x
    const deepgi::RayScene rays(scene);
    const float radius = 0.5f;
    deepgi::AoRayBudget budget;
    budget.min_rays = budget.max_rays = 1 << 17;
    for (double a : {0.02, 0.1, 0.3, 0.6, 0.9, 1.2}) {
        const glm::vec3 x(float(a) * radius, 0.0f, 0.3f);
        const deepgi::AoSample s =
            deepgi::ambient_visibility_at(rays, x, {0, 1, 0}, radius, budget, 12345u);
        const double c = std::min(a, 1.0);
        const double occlusion =
            ((1 + 2 * c * c) * std::acos(c) - 3 * c * std::sqrt(1 - c * c)) / glm::pi<double>();
        const double hit_occlusion = (std::acos(c) - c * std::sqrt(1 - c * c)) / glm::pi<double>();
        INFO("a = " << a << ", standard error " << s.standard_error);
        REQUIRE(s.standard_error < 0.005);
        // Five standard errors: a false failure has odds below one in a million.
        REQUIRE(s.visibility == Approx(1.0 - occlusion).margin(5 * s.standard_error + 1e-4));
        const double hit_error = std::sqrt(hit_occlusion * (1 - hit_occlusion) / s.rays);
        REQUIRE(s.hit_visibility == Approx(1.0 - hit_occlusion).margin(5 * hit_error + 1e-4));
    }
}

TEST_CASE("reference: images do not depend on the thread count", "[reference]") {
    deepgi::Scene scene;
    add_floor(scene, 50.0f);
    add_quad(scene, {0, 0, 50}, {0, 0, -50}, {0, 5, -50}, {0, 5, 50});
    const deepgi::RayScene rays(scene);
    deepgi::Camera camera;
    camera.position = {1.5f, 1.0f, 2.0f};
    camera.yaw = 0.5f;
    camera.pitch = -0.4f;
    auto settings = small_settings(24, 16);
    settings.rays.min_rays = 64;
    settings.rays.max_rays = 1024;
    settings.threads = 1;
    const auto one = deepgi::render_reference(rays, camera, settings);
    settings.threads = 3;
    const auto three = deepgi::render_reference(rays, camera, settings);
    REQUIRE(one.ambient_visibility.pixels == three.ambient_visibility.pixels);
    REQUIRE(one.occlusion_split.pixels == three.occlusion_split.pixels);
    // The corner darkens something: the comparison is not of two blank images.
    float darkest = 1.0f;
    for (float v : one.ambient_visibility.pixels) darkest = std::min(darkest, v);
    REQUIRE(darkest < 0.9f);
    settings.seed = 2;
    const auto reseeded = deepgi::render_reference(rays, camera, settings);
    REQUIRE(reseeded.ambient_visibility.pixels != one.ambient_visibility.pixels);
}

TEST_CASE("reference: the occlusion split sums to 1 - AV and finds occluders only layer 1 sees",
          "[reference]") {
    auto settings = small_settings(64, 36);
    settings.rays.min_rays = settings.rays.max_rays = 512;
    auto split_totals = [&](const char* name) {
        const deepgi::Scene scene = deepgi::make_builtin_scene(name);
        const deepgi::RayScene rays(scene);
        const auto images = deepgi::render_reference(rays, scene.default_camera, settings);
        glm::dvec3 total(0.0);
        for (std::size_t i = 0; i < images.ambient_visibility.pixels.size(); ++i) {
            const glm::dvec3 part(images.occlusion_split.pixels[3 * i],
                                  images.occlusion_split.pixels[3 * i + 1],
                                  images.occlusion_split.pixels[3 * i + 2]);
            REQUIRE(part.x + part.y + part.z ==
                    Approx(1.0 - images.ambient_visibility.pixels[i]).margin(1e-5));
            total += part;
        }
        return total;
    };
    // Floor and wall of a crease are both in plain view: layer 0 sees nearly
    // every occluder (the rest lies past the guard band).
    const glm::dvec3 crease = split_totals("ref-crease");
    INFO("crease split " << crease.x << " " << crease.y << " " << crease.z);
    REQUIRE(crease.x > 0.0);
    REQUIRE(crease.y < 0.01 * crease.x);
    // The bench behind the posts: part of what occludes the floor is hidden
    // from layer 0 and seen by layer 1.
    const glm::dvec3 bench = split_totals("ref-bench");
    INFO("bench split " << bench.x << " " << bench.y << " " << bench.z);
    REQUIRE(bench.y > 0.01 * bench.x);
}

TEST_CASE("reference: deepgi reference writes the images, and bad input writes nothing",
          "[reference]") {
    namespace fs = std::filesystem;
    const fs::path directory = fs::temp_directory_path() / "deepgi_reference_cli_test";
    fs::remove_all(directory);
    const std::string command = std::string(DEEPGI_EXECUTABLE) +
                                " reference --scene ref-slab --size 16x9 --rays 256 "
                                "--min-rays 256 --threads 2 --output " +
                                directory.string() + " > /dev/null";
    REQUIRE(std::system(command.c_str()) == 0);
    const auto visibility = deepgi::read_pfm(directory / "reference-ao-visibility.pfm");
    // The command renders what the library renders with the same settings.
    deepgi::ReferenceSettings settings;
    settings.render.width = 16;
    settings.render.height = 9;
    settings.rays.min_rays = settings.rays.max_rays = 256;
    const deepgi::Scene scene = deepgi::make_builtin_scene("ref-slab");
    const deepgi::RayScene rays(scene);
    const auto images = deepgi::render_reference(rays, scene.default_camera, settings);
    REQUIRE(visibility.pixels == images.ambient_visibility.pixels);
    for (const char* name : {"reference-depth-layer0.pfm", "reference-depth-layer1.pfm",
                             "reference-ao-hit-visibility.pfm", "reference-ao-occlusion-split.pfm",
                             "reference-ao-standard-error.pfm", "reference-ao-rays.pfm"})
        REQUIRE(fs::exists(directory / name));
    fs::remove_all(directory);

    for (const char* arguments : {"--size 16x --output", "--size 16x9 --rays 0 --output",
                                  "--size 16x9 --scene nosuch --output"}) {
        const std::string bad = std::string(DEEPGI_EXECUTABLE) + " reference " + arguments + " " +
                                directory.string() + " 2> /dev/null";
        const int status = std::system(bad.c_str());
        INFO(arguments);
        REQUIRE(WIFEXITED(status));
        REQUIRE(WEXITSTATUS(status) == 2);
        REQUIRE(!fs::exists(directory));
    }
}
