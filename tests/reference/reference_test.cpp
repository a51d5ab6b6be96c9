// The ray-traced reference's ambient visibility against closed forms: an open
// plane, the inside corner of two planes, and the camera rays against
// analytic plane depths; its occlusion split and layer classifier; and the
// `deepgi reference` command. Its irradiance is
// reference_irradiance_test.cpp's and reference_emitter_sampling_test.cpp's.
#include "../support/textbook_camera.hpp"
#include "deepgi/reference.hpp"
#include "deepgi/renderer.hpp"

#include "quad_scene.hpp"
#include "reference_test_support.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <glm/gtc/constants.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

using deepgi::test::add_quad;
using deepgi::test::small_settings;

// The floor y = 0, facing +y, L metres each way.
void add_floor(deepgi::Scene& scene, float l) {
    add_quad(scene, {-l, 0, l}, {l, 0, l}, {l, 0, -l}, {-l, 0, -l});
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
        // The textbook camera (support/textbook_camera.hpp), not the library's.
        const deepgi::test::TextbookCamera textbook =
            deepgi::test::textbook_camera(camera, settings.render);
        int surface = 0;
        for (int y = 0; y < images.ambient_visibility.height; ++y) {
            for (int x = 0; x < images.ambient_visibility.width; ++x) {
                // Independent oracle for the camera ray: where the pixel-centre
                // ray of unit depth meets y = 0, in closed form.
                const glm::vec3 d = deepgi::test::textbook_to_world(
                    textbook, deepgi::test::textbook_camera_ray(textbook, x + 0.5f, y + 0.5f));
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
namespace {

// The floor y = 0 and the wall x = 0 (facing +x), 200 m each way.
deepgi::Scene inside_corner() {
    deepgi::Scene scene;
    const float l = 200.0f;
    add_floor(scene, l);
    add_quad(scene, {0, 0, l}, {0, 0, -l}, {0, l, -l}, {0, l, l});
    return scene;
}

// The corner's occlusion at a = x / r (derived above; 0 from a = 1 on).
double inside_corner_occlusion(double a) {
    const double c = std::min(a, 1.0);
    return ((1 + 2 * c * c) * std::acos(c) - 3 * c * std::sqrt(1 - c * c)) / glm::pi<double>();
}

}  // namespace

TEST_CASE("reference: the inside corner of two planes matches the closed-form integral",
          "[reference]") {
    const deepgi::Scene scene = inside_corner();
    const deepgi::RayScene rays(scene);
    const float radius = 0.5f;
    deepgi::AoRayBudget budget;
    budget.min_rays = budget.max_rays = 1 << 17;
    for (double a : {0.02, 0.1, 0.3, 0.6, 0.9, 1.2}) {
        const glm::vec3 x(float(a) * radius, 0.0f, 0.3f);
        const deepgi::AoSample s =
            deepgi::ambient_visibility_at(rays, x, {0, 1, 0}, radius, budget, 12345u);
        const double c = std::min(a, 1.0);
        const double occlusion = inside_corner_occlusion(a);
        const double hit_occlusion = (std::acos(c) - c * std::sqrt(1 - c * c)) / glm::pi<double>();
        INFO("a = " << a << ", standard error " << s.standard_error);
        REQUIRE(s.standard_error < 0.005);
        // Five standard errors: a false failure has odds below one in a million.
        REQUIRE(s.visibility == Approx(1.0 - occlusion).margin(5 * s.standard_error + 1e-4));
        const double hit_error = std::sqrt(hit_occlusion * (1 - hit_occlusion) / s.rays);
        REQUIRE(s.hit_visibility == Approx(1.0 - hit_occlusion).margin(5 * hit_error + 1e-4));
    }
}

// The directions are stratified in independent sets, and the standard error
// is the spread of the sets' means: over 400 seeds at a fixed 1024 rays, the
// spread of AV in the inside corner above (a = 0.3) must match the root mean
// square reported standard error within 20% (five times the spread's own
// relative uncertainty, about 1 / sqrt(2 * 400)), the mean the closed form
// within five standard errors of the mean, and the spread must be below
// half of what independent directions give, sqrt(var f / N) with var f the
// falloff's variance under cosine weighting (E[f^2] by the midpoint rule).
TEST_CASE("reference: ambient visibility's standard error matches the spread over seeds",
          "[reference]") {
    const deepgi::Scene scene = inside_corner();
    const deepgi::RayScene rays(scene);
    const float radius = 0.5f;
    const double a = 0.3, pi = glm::pi<double>();
    const double occlusion = inside_corner_occlusion(a);
    // E[f^2] over cosine-weighted directions: a direction (theta, phi) from
    // X = (a r, 0, z) reaches the wall at d = a r / (sin theta |cos phi|)
    // when it heads towards it (cos phi < 0); f = 1 - d^2 / r^2 within r.
    double first_moment = 0.0, second_moment = 0.0;
    const int cells = 2000;
    for (int i = 0; i < cells; ++i) {
        const double u = (i + 0.5) / cells;  // sin^2 theta, uniform under cos weighting
        for (int j = 0; j < cells; ++j) {
            const double phi = 2 * pi * (j + 0.5) / cells;
            if (std::cos(phi) >= 0) continue;
            const double d = a / (std::sqrt(u) * -std::cos(phi));  // in units of r
            if (d < 1) {
                first_moment += 1 - d * d;
                second_moment += (1 - d * d) * (1 - d * d);
            }
        }
    }
    first_moment /= double(cells) * cells;
    second_moment /= double(cells) * cells;
    // The sum agrees with the closed form (a check on the sum itself).
    REQUIRE(first_moment == Approx(occlusion).margin(1e-4));
    const int count = 1024, seeds = 400;
    const double independent = std::sqrt((second_moment - occlusion * occlusion) / count);
    deepgi::AoRayBudget budget;
    budget.min_rays = budget.max_rays = count;
    double sum = 0.0, squares = 0.0, error_squares = 0.0;
    for (int seed = 0; seed < seeds; ++seed) {
        const deepgi::AoSample s =
            deepgi::ambient_visibility_at(rays, {float(a) * radius, 0.0f, 0.3f}, {0, 1, 0}, radius,
                                          budget, 700u + std::uint64_t(seed));
        REQUIRE(s.rays == count);
        sum += s.visibility;
        squares += s.visibility * s.visibility;
        error_squares += s.standard_error * s.standard_error;
    }
    const double mean = sum / seeds;
    const double spread = std::sqrt((squares - sum * mean) / (seeds - 1));
    const double reported = std::sqrt(error_squares / seeds);
    INFO("mean AV " << mean << ", expected " << 1 - occlusion << ", spread " << spread
                    << ", reported standard error " << reported << ", independent directions "
                    << independent);
    REQUIRE(mean == Approx(1 - occlusion).margin(5 * spread / std::sqrt(seeds)));
    REQUIRE(spread > 0.8 * reported);
    REQUIRE(spread < 1.25 * reported);
    REQUIRE(spread < 0.5 * independent);
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

TEST_CASE("reference: the layer classifier follows the camera ray through each point",
          "[reference]") {
    // A board (top facing up at y = 1, underside facing down at y = 0.94)
    // over a floor, seen from above and in front. Every expected layer is
    // worked out from the geometry, not from the classifier.
    deepgi::Scene scene;
    add_floor(scene, 50.0f);
    add_quad(scene, {-1, 1, -1}, {1, 1, -1}, {1, 1, -3}, {-1, 1, -3});                  // top
    add_quad(scene, {-1, 0.94f, -1}, {-1, 0.94f, -3}, {1, 0.94f, -3}, {1, 0.94f, -1});  // underside
    const deepgi::RayScene rays(scene);
    deepgi::Camera camera;
    camera.position = {0.0f, 2.0f, 0.0f};
    camera.pitch = glm::radians(-25.0f);
    deepgi::RenderSettings render;
    render.width = 64;
    render.height = 36;
    render.min_separation = 0.5f;
    const deepgi::LayerClassifier layer = deepgi::layer_classifier(rays, camera, render);
    // In plain view: the board's top and the floor past the board (the ray
    // to (0, 0, -8) crosses y = 1 at z = -4, beyond the board).
    CHECK(layer({0.3f, 1.0f, -2.0f}) == 0);
    CHECK(layer({0.0f, 0.0f, -8.0f}) == 0);
    // The underside faces away from the camera: no layer stores it.
    CHECK(layer({0.3f, 0.94f, -2.0f}) == -1);
    // The floor under the board: the ray to (0, 0, -2.5) crosses the top at
    // z = -1.25, so the floor is the next front face, metres behind: layer 1.
    CHECK(layer({0.0f, 0.0f, -2.5f}) == 1);
    // With a separation larger than that gap, layer 1 peels past the floor.
    render.min_separation = 20.0f;
    CHECK(deepgi::layer_classifier(rays, camera, render)({0.0f, 0.0f, -2.5f}) == -1);
    // Behind the camera, and outside the guard-banded frame.
    CHECK(layer({0.0f, 0.0f, 3.0f}) == -1);
    CHECK(layer({40.0f, 0.0f, -8.0f}) == -1);
}

TEST_CASE("reference: deepgi reference writes the images, and bad input writes nothing",
          "[reference]") {
    namespace fs = std::filesystem;
    const fs::path directory = fs::temp_directory_path() / "deepgi_reference_cli_test";
    fs::remove_all(directory);
    const std::string command = std::string(DEEPGI_EXECUTABLE) +
                                " reference --scene ref-slab --size 16x9 --rays 256 "
                                "--min-rays 256 --irradiance-rays 256 --irradiance-min-rays 256 "
                                "--radiosity-radius 0.7 --threads 2 --output " +
                                directory.string() + " > /dev/null";
    REQUIRE(std::system(command.c_str()) == 0);
    const auto visibility = deepgi::read_pfm(directory / "reference-ao-visibility.pfm");
    // The command renders what the library renders with the same settings.
    deepgi::ReferenceSettings settings;
    settings.render.width = 16;
    settings.render.height = 9;
    settings.rays.min_rays = settings.rays.max_rays = 256;
    settings.irradiance = true;
    settings.irradiance_rays.min_rays = settings.irradiance_rays.max_rays = 256;
    settings.radiosity_radius = 0.7f;
    const deepgi::Scene scene = deepgi::make_builtin_scene("ref-slab");
    // The command leaves the AO radius and the separation at auto, which it
    // resolves against the scene as deepgi does.
    settings.render.ao.radius = settings.render.min_separation = deepgi::auto_length;
    settings.render = deepgi::resolve_auto_lengths(settings.render, deepgi::scene_scale(scene));
    const deepgi::RayScene rays(scene);
    const auto images = deepgi::render_reference(rays, scene.default_camera, settings);
    REQUIRE(visibility.pixels == images.ambient_visibility.pixels);
    const auto irradiance = deepgi::read_pfm(directory / "reference-irradiance.pfm");
    REQUIRE(irradiance.channels == 3);
    REQUIRE(irradiance.pixels == images.irradiance.pixels);
    REQUIRE(deepgi::read_pfm(directory / "reference-direct-radiance.pfm").pixels ==
            images.direct_radiance.pixels);
    for (const char* name : {"reference-depth-layer0.pfm", "reference-depth-layer1.pfm",
                             "reference-ao-hit-visibility.pfm", "reference-ao-occlusion-split.pfm",
                             "reference-ao-standard-error.pfm", "reference-ao-rays.pfm",
                             "reference-irradiance-standard-error.pfm",
                             "reference-irradiance-rays.pfm", "reference-irradiance-layer0.pfm",
                             "reference-irradiance-layer1.pfm", "reference-irradiance-neither.pfm"})
        REQUIRE(fs::exists(directory / name));
    // A PNG preview beside each PFM, and nothing else.
    int pfm_count = 0;
    for (const auto& entry : fs::directory_iterator(directory)) {
        const fs::path path = entry.path();
        INFO(path.filename().string());
        REQUIRE((path.extension() == ".pfm" || path.extension() == ".png"));
        if (path.extension() != ".pfm") continue;
        ++pfm_count;
        const fs::path preview = fs::path(path).replace_extension(".png");
        REQUIRE(fs::exists(preview));
        std::ifstream png(preview, std::ios::binary);
        std::string signature(8, '\0');
        png.read(signature.data(), 8);
        CHECK(signature == "\x89PNG\r\n\x1a\n");
    }
    CHECK(pfm_count == 14);
    fs::remove_all(directory);

    for (const char* arguments :
         {"--size 16x --output", "--size 16x9 --rays 0 --output",
          "--size 16x9 --scene nosuch --output", "--size 16x9 --no-ao --no-irradiance --output",
          "--size 16x9 --radiosity-radius 0 --output",
          "--size 16x9 --irradiance-rays 0 --output"}) {
        const std::string bad = std::string(DEEPGI_EXECUTABLE) + " reference " + arguments + " " +
                                directory.string() + " 2> /dev/null";
        const int status = std::system(bad.c_str());
        INFO(arguments);
        REQUIRE(WIFEXITED(status));
        REQUIRE(WEXITSTATUS(status) == 2);
        REQUIRE(!fs::exists(directory));
    }
}
