// The ray-traced reference's emitter sampling: a small emitter's form factor
// far tighter than cosine sampling reaches, agreement with cosine sampling on
// the cornell box, the radius window and shadows, and thread independence.
#include "deepgi/reference.hpp"
#include "deepgi/renderer.hpp"

#include "quad_scene.hpp"
#include "reference_test_support.hpp"

#include <catch2/catch.hpp>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

using deepgi::test::add_quad;
using deepgi::test::exact_budget;
using deepgi::test::require_within_error;
using deepgi::test::small_settings;

namespace {

// A square emitter of radiance `emitted` and side 2a, centred at height h
// over the origin and facing down onto the floor y = 0, with no key light.
deepgi::Scene square_emitter_over_floor(float a, float h, glm::vec3 emitted) {
    deepgi::Scene scene;
    add_quad(scene, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}, {-50, 0, -50}, glm::vec3(0.5f),
             glm::vec3(0.0f));
    add_quad(scene, {-a, h, -a}, {a, h, -a}, {a, h, a}, {-a, h, a}, glm::vec3(0.0f), emitted);
    scene.key_light.intensity = 0.0f;
    return scene;
}

// An independent cosine-only estimate of E at X (pdf cos / pi, so E = pi *
// mean L): first front-facing surface within r, its direct outgoing
// radiance, and the standard error of the mean. Written apart from
// irradiance_at so that the two can be compared.
deepgi::IrradianceSample cosine_only_irradiance(const deepgi::RayScene& rays, glm::vec3 x,
                                                glm::vec3 normal, float radius, int count,
                                                std::uint64_t seed) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(normal));
    const glm::dvec3 helper = std::abs(n.x) < 0.5 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 t = glm::normalize(glm::cross(helper, n)), b = glm::cross(n, t);
    const glm::vec3 origin = x + glm::vec3(n) * 1e-4f;
    std::uint64_t state = seed * 2654435761u + 12345u;
    auto uniform = [&] {
        // A 64-bit linear congruential generator, top 53 bits.
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return double(state >> 11) / 9007199254740992.0;
    };
    glm::dvec3 sum(0.0), squares(0.0);
    for (int k = 0; k < count; ++k) {
        const double u1 = uniform(), u2 = uniform();
        const double phi = 2 * glm::pi<double>() * u2, s = std::sqrt(u1);
        const glm::vec3 w(t * (s * std::cos(phi)) + b * (s * std::sin(phi)) +
                          n * std::sqrt(1.0 - u1));
        const auto hit = rays.intersect(origin, w, 0.0f, radius);
        if (!hit.hit || glm::dot(hit.normal, w) >= 0.0f) continue;
        const glm::dvec3 l = deepgi::direct_outgoing_radiance(rays, hit, origin + w * hit.distance);
        sum += l;
        squares += l * l;
    }
    deepgi::IrradianceSample result;
    const glm::dvec3 mean = sum / double(count);
    result.irradiance = glm::pi<double>() * mean;
    result.standard_error =
        glm::pi<double>() * glm::sqrt((squares / double(count) - mean * mean) / double(count - 1));
    result.rays = result.samples = count;
    return result;
}

}  // namespace

// A small square emitter of side 2a at height h, centred over X and facing it.
// By the contour integral (the lit wall's, reference_irradiance_test.cpp),
// for a rectangle [0, a] x [0, b] in the plane at height c over X, parallel
// to X's surface (n = (0, 1, 0)), the corners relative to X are (0,c,0)
// (a,c,0) (a,c,b) (0,c,b); the edges along x = 0 and z = 0 give R x R'
// perpendicular to n, the other two give
// n.g = a / sqrt(a^2 + c^2), gamma = atan(b / sqrt(a^2 + c^2)) and
// n.g = b / sqrt(b^2 + c^2), gamma = atan(a / sqrt(b^2 + c^2)). So
//   F_corner = [A atan(B') + B atan(A')] / (2 pi) with A = a/sqrt(a^2+c^2),
//   B' = b/sqrt(a^2+c^2), and A', B likewise for b;
// the centred square is four corners with a = b: F = (4 / pi) k atan(k),
// k = a / sqrt(a^2 + h^2) (check: for small a, F = (2a)^2 / (pi h^2), the
// area over pi d^2). E = pi L F.
// Cosine sampling hits the square with probability F, so its estimate is
// pi L times a coin flip and its standard error pi L sqrt(F (1 - F) / N)
// with N rays; sampling the emitter must do far better with the same rays.
TEST_CASE("reference: a small emitter's form factor, far tighter than cosine sampling reaches",
          "[reference]") {
    const glm::vec3 emitted(6.0f, 4.0f, 2.0f);
    const int ray_count = 4096;
    for (const float h : {0.5f, 1.5f}) {
        const float a = 0.05f;
        const deepgi::RayScene rays(square_emitter_over_floor(a, h, emitted));
        REQUIRE(rays.emitters().size() == 2);
        const double k = a / std::sqrt(double(a) * a + double(h) * h);
        const double form_factor = 4.0 / glm::pi<double>() * k * std::atan(k);
        deepgi::IrradianceRayBudget budget;
        budget.min_rays = budget.max_rays = ray_count;
        const auto s = deepgi::irradiance_at(rays, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 5.0f, budget,
                                             31u + std::uint64_t(h * 10));
        INFO("h = " << h << ", F = " << form_factor);
        // Every emitter point passes the tests, so each sample costs two rays.
        REQUIRE(s.rays >= ray_count);
        REQUIRE(s.rays <= ray_count + 1);
        REQUIRE(s.samples == (s.rays + 1) / 2);
        for (int c = 0; c < 3; ++c) {
            const double expected = glm::pi<double>() * emitted[c] * form_factor;
            const double cosine_error = glm::pi<double>() * emitted[c] *
                                        std::sqrt(form_factor * (1 - form_factor) / ray_count);
            INFO("channel " << c << ": E " << s.irradiance[c] << ", expected " << expected
                            << ", standard error " << s.standard_error[c] << ", cosine sampling's "
                            << cosine_error);
            REQUIRE(s.standard_error[c] < 0.05 * cosine_error);
            REQUIRE(s.irradiance[c] == Approx(expected).margin(5 * s.standard_error[c] + 1e-9));
            // A tolerance of a tenth of cosine sampling's standard error
            // (1.4% of E at h = 0.5, 4% at h = 1.5), which cosine sampling
            // itself would miss more than eight times in ten.
            REQUIRE(std::abs(s.irradiance[c] - expected) < 0.1 * cosine_error);
        }
    }
}

// With both techniques on the built-in cornell box (a 0.5 x 0.4 m lamp of
// radiance (12, 10, 7) under the ceiling and a spot key light), irradiance_at
// and the independent cosine-only estimate above agree within their combined
// standard errors, and the combination has the smaller error.
TEST_CASE("reference: emitter sampling agrees with cosine sampling on the cornell box",
          "[reference]") {
    const deepgi::Scene scene = deepgi::make_builtin_scene("cornell");
    const deepgi::RayScene rays(scene);
    REQUIRE(rays.emitters().size() == 2);
    struct Point {
        glm::vec3 position, normal;
        float radius;
    };
    // On the floor, the back wall and the red wall, all of which see the
    // lamp within the radius (the default 1 m, or a wider one).
    const Point points[] = {{{-0.2f, 0.0f, 0.8f}, {0, 1, 0}, 3.0f},
                            {{0.3f, 1.6f, -1.0f}, {0, 0, 1}, 1.0f},
                            {{-1.0f, 1.8f, 0.1f}, {1, 0, 0}, 1.0f},
                            {{-1.0f, 1.2f, -0.5f}, {1, 0, 0}, 3.0f}};
    deepgi::IrradianceRayBudget budget;
    budget.min_rays = budget.max_rays = 16384;
    int index = 0;
    for (const Point& p : points) {
        ++index;
        const auto mis = deepgi::irradiance_at(rays, p.position, p.normal, p.radius, budget,
                                               100u + std::uint64_t(index));
        const auto cosine =
            cosine_only_irradiance(rays, p.position, p.normal, p.radius, 65536, index);
        INFO("point " << index);
        for (int c = 0; c < 3; ++c) {
            INFO("channel " << c << ": E " << mis.irradiance[c] << " +- " << mis.standard_error[c]
                            << ", cosine only " << cosine.irradiance[c] << " +- "
                            << cosine.standard_error[c]);
            REQUIRE(cosine.irradiance[c] > 0.05);
            const double combined = std::hypot(mis.standard_error[c], cosine.standard_error[c]);
            REQUIRE(mis.irradiance[c] == Approx(cosine.irradiance[c]).margin(5 * combined));
            // Cosine sampling with the same 16384 independent rays would have
            // twice the error of its 65536 here. The stratified combination
            // does better everywhere, by 4.5x (on the back wall, where the
            // spot-lit top of the tall block, which only cosine directions
            // find, dominates) to 24x (on the floor).
            REQUIRE(mis.standard_error[c] < 2.0 * cosine.standard_error[c]);
        }
    }
}

// Emitter points obey the radius window: with the square's nearest point
// beyond r there is nothing; with r between h and the square's corners only
// the disk of radius rho = sqrt(r^2 - h^2) under the sphere counts, and that
// disk lies inside the square, so as for the infinite ceiling
//   E = pi L rho^2 / (h^2 + rho^2) = pi L (1 - (h/r)^2),
// far from the whole square's pi L F. A plate between X and the square
// shadows the emitter points. Back faces are covered by the emitter that
// faces away (reference_irradiance_test.cpp).
TEST_CASE("reference: the radius window and shadows cut emitter samples", "[reference]") {
    const glm::vec3 emitted(3.0f, 2.0f, 1.0f);
    const float a = 0.2f, h = 0.5f;
    const deepgi::RayScene rays(square_emitter_over_floor(a, h, emitted));
    deepgi::IrradianceRayBudget budget;
    budget.min_rays = budget.max_rays = 1 << 15;
    const glm::vec3 x(0.0f, 0.0f, 0.0f);
    // Nearest point at h = 0.5 > r: nothing, and no emitter ray is traced.
    const auto outside = deepgi::irradiance_at(rays, x, {0, 1, 0}, 0.49f, budget, 3u);
    REQUIRE(outside.irradiance == glm::dvec3(0.0));
    REQUIRE(outside.standard_error == glm::dvec3(0.0));
    REQUIRE(outside.rays == outside.samples);
    // r = 0.52: rho = 0.143 < a.
    const float radius = 0.52f;
    const double ratio = double(h) / double(radius);
    const auto s = deepgi::irradiance_at(rays, x, {0, 1, 0}, radius, budget, 4u);
    const double k = a / std::sqrt(double(a) * a + double(h) * h);
    const double whole_square = 4.0 / glm::pi<double>() * k * std::atan(k);
    REQUIRE(whole_square > 2.0 * (1.0 - ratio * ratio));  // the two are far apart
    require_within_error(s, glm::pi<double>() * (1.0 - ratio * ratio) * glm::dvec3(emitted));

    deepgi::Scene blocked = square_emitter_over_floor(a, h, emitted);
    add_quad(blocked, {-0.3f, 0.25f, 0.3f}, {0.3f, 0.25f, 0.3f}, {0.3f, 0.25f, -0.3f},
             {-0.3f, 0.25f, -0.3f}, glm::vec3(0.5f), glm::vec3(0.0f));
    const deepgi::RayScene shadowed(blocked);
    const auto dark = deepgi::irradiance_at(shadowed, x, {0, 1, 0}, 2.0f, budget, 5u);
    REQUIRE(dark.irradiance == glm::dvec3(0.0));
    // Every emitter point passed the radius and facing tests: its shadow ray
    // was traced, and found the plate.
    REQUIRE(dark.rays > dark.samples);
}

TEST_CASE("reference: irradiance with emitter sampling does not depend on the thread count",
          "[reference]") {
    const deepgi::Scene scene = deepgi::make_builtin_scene("cornell");
    const deepgi::RayScene rays(scene);
    auto settings = small_settings(24, 14);
    settings.ambient_visibility = false;
    settings.irradiance = true;
    settings.irradiance_rays.min_rays = 256;
    settings.irradiance_rays.max_rays = 2048;
    settings.threads = 1;
    const auto one = deepgi::render_reference(rays, scene.default_camera, settings);
    settings.threads = 3;
    const auto three = deepgi::render_reference(rays, scene.default_camera, settings);
    REQUIRE(one.irradiance.pixels == three.irradiance.pixels);
    REQUIRE(one.irradiance_standard_error.pixels == three.irradiance_standard_error.pixels);
    REQUIRE(one.irradiance_rays.pixels == three.irradiance_rays.pixels);
    // Not two blank images.
    REQUIRE(*std::max_element(one.irradiance.pixels.begin(), one.irradiance.pixels.end()) > 0.1f);
    settings.seed = 2;
    const auto reseeded = deepgi::render_reference(rays, scene.default_camera, settings);
    REQUIRE(reseeded.irradiance.pixels != one.irradiance.pixels);
}
