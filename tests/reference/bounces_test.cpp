// The reference's K-bounce irradiance (irradiance_at's `bounces`, `deepgi
// reference --bounces`) against a closed form, and K = 1 against the
// one-bounce output as it was before bounces existed.
#include "deepgi/image_io.hpp"
#include "deepgi/reference.hpp"
#include "deepgi/renderer.hpp"

#include "quad_scene.hpp"

#include <catch2/catch.hpp>
#include <glm/gtc/constants.hpp>

#include <sys/wait.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace {

using deepgi::test::add_quad;

// FNV-1a (64 bit) of a file's bytes.
std::uint64_t file_hash(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    std::uint64_t hash = 0xcbf29ce484222325ull;
    for (const char c : bytes) {
        hash ^= std::uint64_t(static_cast<unsigned char>(c));
        hash *= 0x100000001b3ull;
    }
    return hash;
}

int exit_status(const std::string& command) {
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

// Two planes h apart facing each other, both of albedo rho and emitting L_e,
// far wider than the path's reach (K R), no key light. By symmetry every
// point of either plane has the same E_k. From a point, the other plane
// within the radius R is a cap of the hemisphere with cos(theta) > h / R, of
// form factor F = 1 - (h/R)^2 (the emitting-ceiling case of
// reference_irradiance_test.cpp); nothing else is within R. So, with L_k the outgoing
// radiance of the K-bounce model and E_0 = 0,
//     L_k = L_e + rho / pi * E_(k-1),   E_k = pi F L_k,
// hence L_k = L_e + rho F L_(k-1), and
//     E_K = pi F L_e (1 + a + a^2 + ... + a^(K-1)),   a = rho F,
// a geometric series in albedo times form factor; K -> infinity gives the
// closed system's pi F L_e / (1 - a).
TEST_CASE("reference: K bounces between facing planes follow the geometric series in rho F",
          "[reference]") {
    const float radius = 0.8f, h = 0.4f;  // h / R = 0.5: F = 0.75
    const glm::vec3 rho(0.8f, 0.5f, 0.2f), emitted(1.0f, 0.6f, 2.0f);
    deepgi::Scene scene;
    const float l = 50.0f;
    add_quad(scene, {-l, 0, l}, {l, 0, l}, {l, 0, -l}, {-l, 0, -l}, rho, emitted);
    add_quad(scene, {-l, h, -l}, {l, h, -l}, {l, h, l}, {-l, h, l}, rho, emitted);
    scene.key_light.intensity = 0.0f;
    const deepgi::RayScene rays(scene);
    const double f = 1.0 - double(h / radius) * double(h / radius);

    deepgi::IrradianceRayBudget budget;
    budget.min_rays = budget.max_rays = budget.ceiling_max_rays = 1 << 16;
    glm::dvec3 previous(0.0);
    for (int k = 1; k <= 4; ++k) {
        const auto s = deepgi::irradiance_at(rays, {0.1f, 0.0f, -0.2f}, {0, 1, 0}, radius, budget,
                                             4321u + std::uint64_t(k), k);
        for (int c = 0; c < 3; ++c) {
            const double a = double(rho[c]) * f;
            double series = 0.0;
            for (int j = 0; j < k; ++j) series += std::pow(a, j);
            const double expected = glm::pi<double>() * f * double(emitted[c]) * series;
            INFO("K = " << k << ", channel " << c << ": E " << s.irradiance[c] << ", expected "
                        << expected << ", standard error " << s.standard_error[c]);
            // Tight enough to tell the bounces apart: the last term a^(K-1)
            // is at least 0.15^3 = 0.34% of E (blue, K = 4), 8% or more on red.
            REQUIRE(s.standard_error[c] <= 0.01 * expected);
            // Five standard errors, plus 0.1% of E for the rays' offset off
            // the planes (as in reference_test_support.hpp).
            REQUIRE(s.irradiance[c] ==
                    Approx(expected).margin(5 * s.standard_error[c] + 1e-3 * expected));
            // Each bounce adds what the series adds, in standard errors.
            if (k > 1 && c == 0) REQUIRE(s.irradiance[c] - previous[c] > 5 * s.standard_error[c]);
        }
        previous = s.irradiance;
    }
}

// One bounce is the estimator it was, draw for draw: a black scene past the
// first surface changes nothing, and the library's default is K = 1.
TEST_CASE("reference: K = 1 is the one-bounce estimator unchanged", "[reference]") {
    const deepgi::Scene scene = deepgi::make_builtin_scene("cornell");
    const deepgi::RayScene rays(scene);
    deepgi::IrradianceRayBudget budget;
    budget.min_rays = budget.max_rays = 2048;
    const glm::vec3 x(0.0f, 0.001f, 0.0f);
    const auto one = deepgi::irradiance_at(rays, x, {0, 1, 0}, 1.0f, budget, 5u, 1);
    const auto plain = deepgi::irradiance_at(rays, x, {0, 1, 0}, 1.0f, budget, 5u);
    REQUIRE(one.irradiance == plain.irradiance);
    REQUIRE(one.rays == plain.rays);
    // Two bounces on cornell's coloured walls add light.
    const auto two = deepgi::irradiance_at(rays, x, {0, 1, 0}, 1.0f, budget, 5u, 2);
    for (int c = 0; c < 3; ++c)
        REQUIRE(two.irradiance[c] >
                one.irradiance[c] + 3 * (two.standard_error[c] + one.standard_error[c]));
}

// `deepgi reference` with and without --bounces 1 writes the very bytes the
// command wrote before --bounces existed (hash recorded from that build, in
// this toolchain: a different libm may move the last bits); --bounces 2
// writes what the library renders with K = 2; bad values exit 2.
TEST_CASE("reference: --bounces 1 writes the old one-bounce output, bad values exit 2",
          "[reference]") {
    namespace fs = std::filesystem;
    const fs::path directory = fs::temp_directory_path() / "deepgi_reference_bounces_test";
    fs::remove_all(directory);
    const std::string base = std::string(DEEPGI_EXECUTABLE) +
                             " reference --scene cornell --size 32x18 --no-ao "
                             "--irradiance-rays 512 --irradiance-min-rays 512 "
                             "--irradiance-ceiling-rays 512 --threads 2 ";
    constexpr std::uint64_t before_bounces = 0x0c10c9c1ddde7057ull;
    for (const char* flag : {"", "--bounces 1 "}) {
        INFO("flags: " << flag);
        REQUIRE(exit_status(base + flag + "--output " + directory.string() + " > /dev/null") == 0);
        CHECK(file_hash(directory / "reference-irradiance.pfm") == before_bounces);
    }

    REQUIRE(exit_status(base + "--bounces 2 --output " + directory.string() + " > /dev/null") == 0);
    deepgi::ReferenceSettings settings;
    settings.render.width = 32;
    settings.render.height = 18;
    settings.ambient_visibility = false;
    settings.irradiance = true;
    settings.irradiance_rays.min_rays = settings.irradiance_rays.max_rays =
        settings.irradiance_rays.ceiling_max_rays = 512;
    settings.bounces = 2;
    settings.threads = 2;
    const deepgi::Scene scene = deepgi::make_builtin_scene("cornell");
    settings.render.ao.radius = settings.render.min_separation = settings.render.radiosity.radius =
        deepgi::auto_length;
    settings.render = deepgi::resolve_auto_lengths(settings.render, deepgi::scene_scale(scene));
    settings.radiosity_radius = settings.render.radiosity.radius;
    const deepgi::RayScene rays(scene);
    const auto images = deepgi::render_reference(rays, scene.default_camera, settings);
    REQUIRE(deepgi::read_pfm(directory / "reference-irradiance.pfm").pixels ==
            images.irradiance.pixels);
    REQUIRE(fs::exists(directory / "reference-irradiance.png"));
    fs::remove_all(directory);

    for (const char* value : {"0", "5", "-1", "two", "1.5"}) {
        INFO("--bounces " << value);
        REQUIRE(exit_status(base + "--bounces " + value + " --output " + directory.string() +
                            " 2> /dev/null") == 2);
        REQUIRE(!fs::exists(directory));
    }
}
