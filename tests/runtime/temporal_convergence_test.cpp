// The temporal filters' convergence targets under a still camera
// (docs/radiosity.md, "How fast a still camera converges"): on cornell,
// atrium and warehouse at the deepgi command line's defaults (lengths `auto`,
// resolved for each scene's size), the blurred E and AO after 16 and
// 64 frames against the same estimator's converged image (76 radiosity taps,
// 256 still frames), measured by tests/runtime/still_convergence.hpp, the
// code the benchmark temporal_convergence prints the docs' table with.
//
// The ctest runs at 160x90 to fit the suite's time; docs/radiosity-studies.md
// ("At the lengths a user gets") has its figures, and compares 160x90 with
// 320x180 at the library's lengths.
#include "deepgi/context.hpp"
#include "deepgi/scene.hpp"
#include "still_convergence.hpp"
#include "support/targets.hpp"

#include <catch2/catch.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace deepgi::test {
namespace {

constexpr int test_width = 160;
constexpr int test_height = 90;

// Targets: E relative RMS <= 5% after 16 frames and <= 2% after 64; fine
// grain on flat surfaces within 1.3x the converged image's; AO the same.
// Known misses carry a regression bound about 10% above the value measured
// at 160x90 at the auto lengths (llvmpipe, LLVM 15); the table goes to
// temporal-convergence-targets.md, printed by the ctest entry
// "deepgi_temporal_convergence_targets_missed" (support/targets.hpp).
spiral::test::TargetTable& targets() {
    using spiral::test::KnownMiss;
    const std::string at = "measured at 160x90";
    static spiral::test::TargetTable table(
        "temporal-convergence-targets.md",
        {
            // The gather's disk widened towards the ball's projection
            // (docs/radiosity.md, "The screen disk") spreads the same taps
            // wider: cornell's E went from 0.0734 / 0.0298 to these, and
            // warehouse's from 0.3028 / 0.0655.
            {"cornell/E relative RMS/16 frames", KnownMiss{0.088, at + ": 0.0796"}},
            {"cornell/E relative RMS/64 frames", KnownMiss{0.037, at + ": 0.0332"}},
            {"cornell/AO RMS / mean occlusion/16 frames", KnownMiss{0.074, at + ": 0.0673"}},
            // Warehouse at its 6 m auto radius (0.75 x its 8 m height);
            // its fine grain, on 113 flat pixels, moves with the
            // realisation (docs/radiosity-studies.md, "The auto radius of a
            // low, wide interior"). The prefiltered levels took the
            // converged image's grain from 4.97% to 1.16% and the image's
            // after 16 frames from 31.5% to 22.4%, so the ratios rose
            // (docs/radiosity.md, "Prefiltered levels").
            {"warehouse/E relative RMS/16 frames", KnownMiss{0.39, at + ": 0.3545"}},
            {"warehouse/E relative RMS/64 frames", KnownMiss{0.091, at + ": 0.0828"}},
            {"warehouse/E fine grain / converged's/16 frames", KnownMiss{19.6, at + ": 17.82"}},
            {"warehouse/E fine grain / converged's/64 frames", KnownMiss{7.9, at + ": 7.21"}},
        });
    return table;
}

// The fine grain needs flat pixels, and for E a converged image with light
// on them. At 160x90 the 9x9 window is twice as wide in the scene as at
// 320x180: atrium keeps 187 flat pixels, warehouse 113. At the library's 1 m
// radiosity radius warehouse's were all unlit (the converged E exactly 0);
// at its auto radius (6 m) they are lit, so every scene has an E grain.
constexpr std::size_t min_flat_pixels = 100;

TEST_CASE(
    "temporal_convergence: a still camera's blurred E and AO approach the converged image "
    "within the targets after 16 and 64 frames",
    "[temporal_convergence]") {
    HeadlessContext context;
    // The command line's defaults, as the benchmark uses: lengths follow the
    // scene.
    RenderSettings settings = with_auto_lengths({});
    settings.width = test_width;
    settings.height = test_height;
    for (const std::string name : {"cornell", "atrium", "warehouse"}) {
        const Scene scene = make_builtin_scene(name);
        const convergence::StillConvergence run =
            convergence::measure_still_convergence(scene, settings, {16, 64});
        REQUIRE(run.rows.size() == 2);
        const convergence::StillFigures& at16 = run.rows[0];
        const convergence::StillFigures& at64 = run.rows[1];
        INFO(name << " at " << test_width << "x" << test_height << ", " << run.flat_pixels
                  << " flat pixels of " << run.pixels << "; E RMS " << at16.e_rms << " / "
                  << at64.e_rms << ", AO RMS " << at16.ao_rms << " / " << at64.ao_rms
                  << " after 16 / 64 frames; fine grain E " << at16.e_grain << " / " << at64.e_grain
                  << " (converged " << run.converged_e_grain << "), AO " << at16.ao_grain << " / "
                  << at64.ao_grain << " (converged " << run.converged_ao_grain << ")");
        // The measurement has something to measure: flat pixels for the fine
        // grain, and AO with grain of its own there.
        REQUIRE(run.flat_pixels >= min_flat_pixels);
        CHECK(run.converged_ao_grain > 0.0);
        REQUIRE(run.converged_e_grain > 0.0);
        // It keeps converging: from 16 to 64 frames 1/sqrt(frames) halves the
        // error; a filter that froze (the old 8-step cycle) would not.
        CHECK(at64.e_rms <= 0.6 * at16.e_rms);
        CHECK(at64.ao_rms <= 0.6 * at16.ao_rms);
        for (const convergence::StillFigures* row : {&at16, &at64}) {
            const std::string stage = std::to_string(row->frames) + " frames";
            targets().check_at_most(name, "E relative RMS", stage, row->e_rms,
                                    row->frames == 16 ? 0.05 : 0.02);
            targets().check_at_most(name, "E fine grain / converged's", stage,
                                    row->e_grain / run.converged_e_grain, 1.3);
            targets().check_at_most(name, "AO RMS / mean occlusion", stage, row->ao_rms,
                                    row->frames == 16 ? 0.05 : 0.02);
            targets().check_at_most(name, "AO fine grain / converged's", stage,
                                    row->ao_grain / run.converged_ao_grain, 1.3);
        }
        targets().write();
    }
}

}  // namespace
}  // namespace deepgi::test
