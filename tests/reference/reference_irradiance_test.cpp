// The ray-traced reference's irradiance against closed forms: form factors of
// lit and emitting planes, the key light's cone, falloff and shadow, the light
// a spot- or point-lit square reflects, and its standard error over seeds.
// Emitter sampling is reference_emitter_sampling_test.cpp's.
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

// A wall of uniform outgoing radiance L in the plane z = zw, facing -z, over
// x in [x1, x2] and y in [0, b], standing on the floor y = 0. X lies on the
// floor at (x0, 0, z0), normal +y, c = zw - z0 in front of the wall. With
// cosine-weighted rays E = integral of L cos(theta) dw = pi L F, F the form
// factor from the differential area at X to the wall.
//
// F by the contour integral (Stokes): for a polygon P1..Pk seen from X, with
// R_i = P_i - X, F = 1/(2 pi) * sum_i gamma_i (n . g_i), gamma_i the angle
// between R_i and R_i+1 and g_i the unit normal of the plane through X and
// edge i, (R_i x R_i+1) / |R_i x R_i+1| (signs fixed by the orientation).
// For the rectangle x in [0, a], y in [0, b] at distance c, corners
// (0,0,c) (a,0,c) (a,b,c) (0,b,c) relative to X, and n = (0,1,0):
//   bottom edge: R1 x R2 = (0, ac, 0), n.g = 1, gamma = atan(a / c);
//   right and left edges: R x R' has no y component, n.g = 0;
//   top edge: R3 x R4 = (0, -ac, ab), n.g = -c / sqrt(b^2 + c^2),
//             gamma = atan(a / sqrt(b^2 + c^2)).
// So  F(a) = 1/(2 pi) [atan(a/c) - c/sqrt(b^2+c^2) * atan(a/sqrt(b^2+c^2))],
// odd in a; a wall from x1 to x2 seen from x0 gives F(x2 - x0) - F(x1 - x0).
// Check: b, a -> infinity gives 1/4, half of the 1/2 of an infinite wall.
TEST_CASE("reference: a lit wall onto a floor matches the analytic form factor", "[reference]") {
    const float zw = 1.0f, x1 = -0.3f, x2 = 0.7f, b = 0.6f;
    const glm::vec3 rho(0.8f, 0.4f, 0.2f), emitted(1.0f, 0.5f, 0.25f);
    auto form_factor = [&](double x0, double c) {
        const double h = std::sqrt(double(b) * b + c * c);
        auto f = [&](double a) {
            return (std::atan(a / c) - c / h * std::atan(a / h)) / (2 * glm::pi<double>());
        };
        return f(x2 - x0) - f(x1 - x0);
    };
    // The emitting wall, and the same wall lit head-on by a directional key
    // light travelling along +z (it grazes the floor, which stays unlit), so
    // its radiance is rho / pi * intensity * colour with a cosine of 1.
    for (const bool lit : {false, true}) {
        deepgi::Scene scene;
        add_quad(scene, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}, {-50, 0, -50}, glm::vec3(0.5f),
                 glm::vec3(0.0f));
        add_quad(scene, {x2, 0, zw}, {x1, 0, zw}, {x1, b, zw}, {x2, b, zw},
                 lit ? rho : glm::vec3(0.0f), lit ? glm::vec3(0.0f) : emitted);
        scene.key_light.kind = deepgi::LightKind::directional;
        scene.key_light.direction = {0, 0, 1};
        scene.key_light.colour = glm::vec3(1.0f);
        scene.key_light.intensity = 3.0f;
        const deepgi::RayScene rays(scene);
        const glm::dvec3 radiance =
            lit ? glm::dvec3(rho) / glm::pi<double>() * 3.0 : glm::dvec3(emitted);
        for (double x0 : {0.0, 0.2, -0.5, 1.1}) {
            for (double c : {0.15, 0.4, 0.9}) {
                const glm::vec3 x(float(x0), 0.0f, float(zw - c));
                const auto s = deepgi::irradiance_at(rays, x, {0, 1, 0}, 50.0f, exact_budget(),
                                                     777u + std::uint64_t(x0 * 100 + c * 10));
                INFO((lit ? "lit" : "emitting") << " wall, x0 = " << x0 << ", c = " << c);
                require_within_error(s, glm::pi<double>() * form_factor(x0, c) * radiance);
            }
        }
    }
}

// An emitting ceiling of radiance L at height h over X, facing down and far
// wider than the radius r. A ray at angle theta from the normal meets it at
// h / cos(theta), within r iff cos(theta) > h / r = cos(theta0), so
//   E = L * integral over the cap theta < theta0 of cos dw = pi L sin^2(theta0)
//     = pi L (1 - (h/r)^2),   and 0 once h >= r.
TEST_CASE("reference: an emitting plane facing the point gives pi L (1 - (h/r)^2)", "[reference]") {
    const glm::vec3 emitted(2.0f, 1.0f, 0.5f);
    const float radius = 0.8f;
    for (double ratio : {0.1, 0.5, 0.9, 1.2}) {
        const float h = float(ratio) * radius;
        deepgi::Scene scene;
        add_quad(scene, {-100, 0, 100}, {100, 0, 100}, {100, 0, -100}, {-100, 0, -100},
                 glm::vec3(0.5f), glm::vec3(0.0f));
        add_quad(scene, {-100, h, -100}, {100, h, -100}, {100, h, 100}, {-100, h, 100},
                 glm::vec3(0.0f), emitted);
        const deepgi::RayScene rays(scene);
        const auto s = deepgi::irradiance_at(rays, {0.1f, 0.0f, -0.2f}, {0, 1, 0}, radius,
                                             exact_budget(), 99u);
        INFO("h / r = " << ratio);
        if (ratio >= 1.0) {
            REQUIRE(s.irradiance == glm::dvec3(0.0));
        } else {
            require_within_error(s,
                                 glm::pi<double>() * (1.0 - ratio * ratio) * glm::dvec3(emitted));
        }
    }
}

TEST_CASE("reference: an open lit floor receives no irradiance, nor does the back of an emitter",
          "[reference]") {
    deepgi::Scene scene;
    add_quad(scene, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}, {-50, 0, -50}, glm::vec3(0.9f),
             glm::vec3(0.0f));
    // An emitting wall that faces away from the points in front of it (+z),
    // which sit at z < 1: the gather's facing test drops it, so must we.
    add_quad(scene, {-1, 0, 1}, {1, 0, 1}, {1, 1, 1}, {-1, 1, 1}, glm::vec3(0.9f), glm::vec3(5.0f));
    scene.key_light.kind = deepgi::LightKind::directional;
    scene.key_light.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    const deepgi::RayScene rays(scene);
    deepgi::IrradianceRayBudget budget;
    budget.min_rays = budget.max_rays = 4096;
    // The floor is lit (so it is not the light that is missing).
    const deepgi::RayScene::Hit down = rays.intersect({0, 1, -3}, {0, -1, 0}, 0.0f, 10.0f);
    REQUIRE(down.hit);
    REQUIRE(deepgi::direct_outgoing_radiance(rays, down, {0, 0, -3}).x > 0.1);
    for (glm::vec3 x : {glm::vec3(0, 0, -3), glm::vec3(0.5f, 0, 0.8f), glm::vec3(-0.2f, 0, 0.2f)}) {
        const auto s = deepgi::irradiance_at(rays, x, {0, 1, 0}, 5.0f, budget, 5u);
        REQUIRE(s.irradiance == glm::dvec3(0.0));
        REQUIRE(s.standard_error == glm::dvec3(0.0));
    }
    // Behind the wall (z > 1) the emitter faces the point and does light it.
    const auto behind = deepgi::irradiance_at(rays, {0, 0, 1.3f}, {0, 1, 0}, 5.0f, budget, 5u);
    REQUIRE(behind.irradiance.x > 0.5);
}

// A spot light h above a floor, pointing down: at horizontal distance s the
// point is d = sqrt(h^2 + s^2) away and both the floor's cosine and the
// cosine to the spot axis are h / d, so inside the inner cone
//   L = rho / pi * I / d^2 * h / d,
// 0 outside the outer cone, and 0 under a blocker.
TEST_CASE("reference: the key light's spot cone, falloff and shadow", "[reference]") {
    const float h = 2.0f;
    const glm::vec3 rho(0.6f, 0.5f, 0.4f);
    deepgi::Scene scene;
    add_quad(scene, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}, {-50, 0, -50}, rho, glm::vec3(0.0f));
    // A 20 cm blocker plate at height 1 over the origin: off the light paths
    // of the first spot position, right under the second.
    add_quad(scene, {-0.1f, 1, 0.1f}, {0.1f, 1, 0.1f}, {0.1f, 1, -0.1f}, {-0.1f, 1, -0.1f},
             glm::vec3(0.5f), glm::vec3(0.0f));
    scene.key_light.kind = deepgi::LightKind::spot;
    scene.key_light.position = {3.0f, h, 0.0f};
    scene.key_light.direction = {0, -1, 0};
    scene.key_light.colour = glm::vec3(1.0f);
    scene.key_light.intensity = 10.0f;
    scene.key_light.inner_cone = glm::radians(40.0f);
    scene.key_light.outer_cone = glm::radians(50.0f);
    const deepgi::RayScene rays(scene);
    auto radiance_at = [&](glm::vec3 p) {
        const auto hit = rays.intersect(p + glm::vec3(0, 0.5f, 0), {0, -1, 0}, 0.0f, 1.0f);
        REQUIRE(hit.hit);
        return deepgi::direct_outgoing_radiance(rays, hit, p);
    };
    // Inside the inner cone: tan 40 deg * 2 = 1.68.
    for (float s : {0.0f, 0.7f, 1.5f}) {
        const double d = std::sqrt(double(h) * h + double(s) * s);
        const glm::dvec3 expected = glm::dvec3(rho) / glm::pi<double>() * 10.0 / (d * d) * (h / d);
        const glm::dvec3 got = radiance_at({3.0f + s, 0.0f, 0.0f});
        INFO("s = " << s);
        for (int c = 0; c < 3; ++c) REQUIRE(got[c] == Approx(expected[c]).epsilon(1e-5));
    }
    // Between the cones the smoothstep lies strictly between 0 and full.
    {
        const float s = 2.0f;  // 45 degrees off the axis
        const double d = std::sqrt(double(h) * h + double(s) * s);
        const double full = rho.x / glm::pi<double>() * 10.0 / (d * d) * (h / d);
        const double got = radiance_at({3.0f + s, 0.0f, 0.0f}).x;
        REQUIRE(got > 0.05 * full);
        REQUIRE(got < 0.95 * full);
    }
    // Outside the outer cone (tan 50 deg * 2 = 2.38): nothing.
    REQUIRE(radiance_at({3.0f + 2.6f, 0.0f, 0.0f}) == glm::dvec3(0.0));
    // The spot moved over the blocker: the floor right under it is in shadow.
    scene.key_light.position = {0.0f, h, 0.0f};
    const deepgi::RayScene shadowed(scene);
    const auto hit = shadowed.intersect({0.0f, 0.5f, 0.0f}, {0, -1, 0}, 0.0f, 1.0f);
    REQUIRE(hit.hit);
    REQUIRE(deepgi::direct_outgoing_radiance(shadowed, hit, {0.0f, 0.0f, 0.0f}) == glm::dvec3(0.0));
    // At x = 0.5 the light passes the blocker's height at x = 0.25: lit again.
    const auto beside = shadowed.intersect({0.5f, 0.5f, 0.0f}, {0, -1, 0}, 0.0f, 1.0f);
    REQUIRE(deepgi::direct_outgoing_radiance(shadowed, beside, {0.5f, 0.0f, 0.0f}).x > 0.1);
}

TEST_CASE("reference: irradiance images do not depend on the thread count", "[reference]") {
    deepgi::Scene scene;
    add_quad(scene, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}, {-50, 0, -50}, glm::vec3(0.7f),
             glm::vec3(0.0f));
    add_quad(scene, {0, 0, 50}, {0, 0, -50}, {0, 5, -50}, {0, 5, 50}, glm::vec3(0.8f, 0.2f, 0.2f),
             glm::vec3(0.0f));
    scene.key_light.kind = deepgi::LightKind::directional;
    scene.key_light.direction = glm::normalize(glm::vec3(-1.0f, -1.0f, 0.3f));
    const deepgi::RayScene rays(scene);
    deepgi::Camera camera;
    camera.position = {1.5f, 1.0f, 2.0f};
    camera.yaw = 0.5f;
    camera.pitch = -0.4f;
    auto settings = small_settings(24, 16);
    settings.ambient_visibility = false;
    settings.irradiance = true;
    settings.irradiance_rays.min_rays = 64;
    settings.irradiance_rays.max_rays = 1024;
    settings.threads = 1;
    const auto one = deepgi::render_reference(rays, camera, settings);
    settings.threads = 3;
    const auto three = deepgi::render_reference(rays, camera, settings);
    REQUIRE(one.irradiance.pixels == three.irradiance.pixels);
    REQUIRE(one.irradiance_standard_error.pixels == three.irradiance_standard_error.pixels);
    REQUIRE(one.irradiance_rays.pixels == three.irradiance_rays.pixels);
    REQUIRE(one.direct_radiance.pixels == three.direct_radiance.pixels);
    // The lit wall bounces red onto the floor: not two blank images.
    float reddest = 0.0f;
    for (std::size_t i = 0; i < one.irradiance.pixels.size(); i += 3)
        reddest = std::max(reddest, one.irradiance.pixels[i] - one.irradiance.pixels[i + 1]);
    REQUIRE(reddest > 0.05f);
    settings.seed = 2;
    const auto reseeded = deepgi::render_reference(rays, camera, settings);
    REQUIRE(reseeded.irradiance.pixels != one.irradiance.pixels);
}

namespace {

// A square of albedo rho and side 2a at y = 0, facing up, the only surface,
// under a key light at height H straight above its centre.
deepgi::Scene lit_square(deepgi::LightKind kind, float a, float h, glm::vec3 rho) {
    deepgi::Scene scene;
    add_quad(scene, {-a, 0, a}, {a, 0, a}, {a, 0, -a}, {-a, 0, -a}, rho, glm::vec3(0.0f));
    scene.key_light.kind = kind;
    scene.key_light.position = {0.0f, h, 0.0f};
    scene.key_light.direction = {0, -1, 0};
    scene.key_light.colour = glm::vec3(1.0f);
    scene.key_light.intensity = 10.0f;
    scene.key_light.inner_cone = glm::radians(25.0f);
    scene.key_light.outer_cone = glm::radians(30.0f);
    return scene;
}

}  // namespace

// With the inner cone wider than the square (tan 25 deg * 1.5 = 0.70 over a
// half diagonal of 0.57), a point y = (x, 0, z) of the square, d from the
// light, has the cosine h / d to the light and to the spot axis, so
//   L(y) = rho / pi * I / d^2 * h / d,
// and X (normal n) receives E = integral over the square of
//   L(y) cos_x cos_y / s^2 dA,  s = |y - X|, cos_x = n.(y - X)/s,
//   cos_y = X_y / s.
// The test sums that by the midpoint rule on 400 x 400 cells (a smooth
// integrand: the error is far below the Monte Carlo tolerance). The same
// holds for a point light, which has no cone. The square fills much of X's
// hemisphere, so 2^18 rays give a standard error near 0.3% of E and the
// 5-sigma tolerance stays below 2%. No other test integrates a
// spot or point light's reflected light over the hemisphere.
TEST_CASE("reference: a spot-lit square seen from a point matches the integral over its area",
          "[reference]") {
    const float a = 0.4f, h = 1.5f;
    const glm::dvec3 rho(0.8, 0.6, 0.4);
    struct Case {
        deepgi::LightKind kind;
        glm::vec3 x, normal;
        float radius;
    };
    // Facing straight down, or tilted towards the square's centre.
    const Case cases[] = {
        {deepgi::LightKind::spot, {0.2f, 0.25f, 0.1f}, {0, -1, 0}, 1.0f},
        {deepgi::LightKind::spot, {-0.3f, 0.6f, -0.2f}, {0.3f, -0.6f, 0.2f}, 5.0f},
        {deepgi::LightKind::point, {0.2f, 0.25f, 0.1f}, {0, -1, 0}, 1.0f},
        {deepgi::LightKind::point, {0.1f, 0.7f, 0.3f}, {-0.1f, -0.7f, -0.3f}, 5.0f}};
    int index = 0;
    for (const Case& c : cases) {
        ++index;
        const deepgi::RayScene rays(lit_square(c.kind, a, h, glm::vec3(rho)));
        const glm::dvec3 x(c.x);
        const glm::dvec3 n = glm::normalize(glm::dvec3(c.normal));
        const int cells = 400;
        const double cell = 2.0 * a / cells;
        double integral = 0.0, smallest_cos_x = 1.0, farthest = 0.0;
        for (int i = 0; i < cells; ++i) {
            for (int j = 0; j < cells; ++j) {
                const glm::dvec3 y(-a + (i + 0.5) * cell, 0.0, -a + (j + 0.5) * cell);
                const double d = glm::length(glm::dvec3(0.0, h, 0.0) - y);
                const glm::dvec3 v = y - x;
                const double s = glm::length(v);
                const double cos_x = glm::dot(n, v) / s, cos_y = x.y / s;
                smallest_cos_x = std::min(smallest_cos_x, cos_x);
                farthest = std::max(farthest, s);
                integral += 10.0 / (d * d) * (h / d) / glm::pi<double>() * cos_x * cos_y / (s * s) *
                            cell * cell;
            }
        }
        // All of the square lies above X's horizon and within the radius.
        REQUIRE(smallest_cos_x > 0.0);
        REQUIRE(farthest < c.radius);
        deepgi::IrradianceRayBudget budget;
        budget.min_rays = budget.max_rays = 1 << 18;
        const auto s = deepgi::irradiance_at(rays, c.x, glm::vec3(n), c.radius, budget,
                                             500u + std::uint64_t(index));
        INFO("case " << index << ": samples " << s.samples << ", rays " << s.rays);
        for (int k = 0; k < 3; ++k) {
            INFO("channel " << k << ": E " << s.irradiance[k] << " +- " << s.standard_error[k]
                            << ", integral " << rho[k] * integral);
            REQUIRE(s.standard_error[k] < 0.005 * rho[k] * integral);
            REQUIRE(s.irradiance[k] == Approx(rho[k] * integral).margin(5 * s.standard_error[k]));
        }
    }
}

// The standard error is honest: over many seeds, E spreads as the reported
// standard errors say it should. The point X on a floor sees a wall lit
// head-on (radiance L_w = rho I / pi, edges on all four sides) and, in one
// scene, a small square emitter overhead, so E has a closed form, pi L_w
// F_wall + pi L_e F_square (the lit wall's form factor above, the square's in
// reference_emitter_sampling_test.cpp), as an
// independent check of the mean. With a fixed budget the spread of E over
// 400 seeds must match the root mean square of the reported standard errors
// within 20% (five times the spread's own relative uncertainty of about
// 1 / sqrt(2 * 400)). And the points are stratified: the spread is less than
// half of what independent cosine directions give with the same samples,
// pi L_w sqrt(F (1 - F) / N) (a coin flip on the wall).
//
// With the adaptive stop every seed stops at its first reading below the
// target over the margin, so the reading it reports is picked for being low
// (about 1.2x too low with 16 sets here); the margin is there to keep the
// actual spread below the target all the same, which is what is required,
// with the reading within 0.8x to 1.4x of the spread.
TEST_CASE("reference: irradiance's standard error matches the spread of E over seeds",
          "[reference]") {
    const float zw = 1.0f, x1 = -0.3f, x2 = 0.7f, b = 0.6f, a = 0.1f, h = 0.7f;
    const glm::vec3 rho(0.8f, 0.4f, 0.2f), emitted(3.0f, 2.0f, 1.0f);
    const double pi = glm::pi<double>();
    const double x0 = 0.2, c = 0.4;
    const double diagonal = std::sqrt(double(b) * b + c * c);
    auto wall = [&](double u) {
        return (std::atan(u / c) - c / diagonal * std::atan(u / diagonal)) / (2 * pi);
    };
    const double wall_factor = wall(x2 - x0) - wall(x1 - x0);
    const double k = a / std::sqrt(double(a) * a + double(h) * h);
    const double square_factor = 4.0 / pi * k * std::atan(k);
    const glm::dvec3 wall_radiance = glm::dvec3(rho) / pi * 3.0;
    for (const bool with_emitter : {false, true}) {
        deepgi::Scene scene;
        add_quad(scene, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}, {-50, 0, -50}, glm::vec3(0.5f),
                 glm::vec3(0.0f));
        add_quad(scene, {x2, 0, zw}, {x1, 0, zw}, {x1, b, zw}, {x2, b, zw}, rho, glm::vec3(0.0f));
        // Centred over X, facing down, above the wall's top edge so that the
        // key light (along +z) leaves the wall unshadowed.
        const float sx = float(x0), sz = float(zw - c);
        if (with_emitter)
            add_quad(scene, {sx - a, h, sz - a}, {sx + a, h, sz - a}, {sx + a, h, sz + a},
                     {sx - a, h, sz + a}, glm::vec3(0.0f), emitted);
        scene.key_light.kind = deepgi::LightKind::directional;
        scene.key_light.direction = {0, 0, 1};
        scene.key_light.colour = glm::vec3(1.0f);
        scene.key_light.intensity = 3.0f;
        const deepgi::RayScene rays(scene);
        REQUIRE(rays.emitters().size() == (with_emitter ? 2u : 0u));
        const glm::dvec3 expected =
            pi * wall_factor * wall_radiance +
            (with_emitter ? pi * square_factor * glm::dvec3(emitted) : glm::dvec3(0.0));

        for (const bool adaptive : {false, true}) {
            deepgi::IrradianceRayBudget budget;
            budget.min_rays = adaptive ? 512 : 2048;
            budget.max_rays = budget.ceiling_max_rays = adaptive ? 1 << 16 : 2048;
            // An absolute target that every seed reaches well within the cap.
            const double target = 0.003;
            budget.target_relative_error = 0.0;
            budget.target_absolute_error = budget.largest_error = target;
            const int seeds = 400;
            glm::dvec3 sum(0.0), squares(0.0), error_squares(0.0);
            double samples = 0.0, fewest = 1e30, most = 0.0;
            for (int seed = 0; seed < seeds; ++seed) {
                const auto s = deepgi::irradiance_at(rays, {sx, 0.0f, sz}, {0, 1, 0}, 5.0f, budget,
                                                     9000u + std::uint64_t(seed));
                sum += s.irradiance;
                squares += s.irradiance * s.irradiance;
                error_squares += s.standard_error * s.standard_error;
                samples += s.samples;
                fewest = std::min(fewest, double(s.samples));
                most = std::max(most, double(s.samples));
            }
            const glm::dvec3 mean = sum / double(seeds);
            const glm::dvec3 spread = glm::sqrt((squares - sum * mean) / double(seeds - 1));
            const glm::dvec3 reported = glm::sqrt(error_squares / double(seeds));
            INFO((with_emitter ? "wall and emitter" : "wall")
                 << (adaptive ? ", adaptive" : "") << ": samples " << fewest << " to " << most);
            // The adaptive runs must stop by the rule, at different counts.
            if (adaptive) {
                REQUIRE(most > fewest);
                REQUIRE(most < (1 << 15));
            }
            for (int ch = 0; ch < 3; ++ch) {
                INFO("channel " << ch << ": mean E " << mean[ch] << ", expected " << expected[ch]
                                << ", spread " << spread[ch] << ", reported standard error "
                                << reported[ch]);
                REQUIRE(mean[ch] == Approx(expected[ch]).margin(5 * spread[ch] / std::sqrt(seeds)));
                REQUIRE(spread[ch] > 0.8 * reported[ch]);
                REQUIRE(spread[ch] < (adaptive ? 1.4 : 1.25) * reported[ch]);
                if (adaptive) REQUIRE(spread[ch] < target);
                if (!with_emitter && !adaptive) {
                    const double n = samples / seeds;
                    const double independent =
                        pi * wall_radiance[ch] * std::sqrt(wall_factor * (1 - wall_factor) / n);
                    INFO("independent cosine directions: " << independent);
                    REQUIRE(spread[ch] < 0.5 * independent);
                }
            }
        }
    }
}
