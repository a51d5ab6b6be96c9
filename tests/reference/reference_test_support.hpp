// Shared by the reference tests: small-image settings and the check of an
// irradiance sample against a closed form within its own standard error.
#pragma once

#include "deepgi/reference.hpp"

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

namespace deepgi::test {

// Small images: a 0.5 m AO radius, 256 rays a pixel, two threads.
inline ReferenceSettings small_settings(int width, int height) {
    ReferenceSettings settings;
    settings.render.width = width;
    settings.render.height = height;
    settings.render.ao.radius = 0.5f;
    settings.rays.min_rays = settings.rays.max_rays = 256;
    settings.threads = 2;
    return settings;
}

// Irradiance budget for the closed-form cases: enough rays for a standard
// error of 3% of E or less, so a 5-sigma margin still catches a wrong factor.
inline IrradianceRayBudget exact_budget() {
    IrradianceRayBudget budget;
    budget.min_rays = budget.max_rays = 1 << 16;
    return budget;
}

inline void require_within_error(const IrradianceSample& s, glm::dvec3 expected) {
    for (int c = 0; c < 3; ++c) {
        INFO("channel " << c << ": E " << s.irradiance[c] << ", expected " << expected[c]
                        << ", standard error " << s.standard_error[c]);
        // The error estimate itself must be small enough to mean something.
        REQUIRE(s.standard_error[c] <= 0.03 * expected[c] + 1e-9);
        // Five standard errors: a false failure has odds below one in a million.
        // Plus 0.1% of E: rays leave X up to 1e-4 m off the floor, where the
        // closed forms put X on it (the lit wall loses 1.2e-4 of E that way
        // at c = 0.9), and stratified sampling brings the standard error of
        // these smooth cases below that.
        REQUIRE(s.irradiance[c] ==
                Approx(expected[c]).margin(5 * s.standard_error[c] + 1e-3 * expected[c] + 1e-6));
    }
}

}  // namespace deepgi::test
