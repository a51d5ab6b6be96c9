// temporal_convergence: how fast a still camera's blurred E and AO approach
// the same estimator's converged image (docs/radiosity.md, "How fast a still
// camera converges"), as a table per scene at default settings. The
// measurement and its figures are tests/runtime/still_convergence.hpp's,
// shared with the ctest that checks the targets.
#include "bench_harness.hpp"
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/renderer.hpp"
#include "still_convergence.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>

int main(int argc, char** argv) {
    deepgi::bench::Options options;
    options.size = "320x180";
    options.scenes = {"cornell", "atrium", "warehouse"};
    std::vector<int> counts{16, 64};
    int converged_frames = deepgi::convergence::default_converged_frames;
    int converged_taps = deepgi::convergence::default_converged_taps;
    CLI::App app{"temporal_convergence: still-camera E and AO against the converged image"};
    deepgi::bench::add_options(app, options);
    app.add_option("--frames-list", counts, "still frame counts at which to measure")
        ->delimiter(',');
    app.add_option("--converged-frames", converged_frames, "frames of the converged image");
    app.add_option("--converged-taps", converged_taps, "radiosity taps of the converged image");
    CLI11_PARSE(app, argc, argv);
    return deepgi::bench::run("temporal_convergence", [&] {
        deepgi::bench::finish(options);
        for (int n : counts)
            if (n < 1) throw deepgi::InputError("--frames-list: counts must be >= 1");
        if (converged_frames < 1) throw deepgi::InputError("--converged-frames must be >= 1");
        if (converged_taps < 1) throw deepgi::InputError("--converged-taps must be >= 1");
        const deepgi::RenderSettings settings = deepgi::bench::settings_for(options);
        deepgi::validate(settings);
        deepgi::HeadlessContext context;
        // The measurement renders the counts in order, from one renderer.
        std::sort(counts.begin(), counts.end());
        counts.erase(std::unique(counts.begin(), counts.end()), counts.end());
        fmt::print(
            "| scene | frames | E rel. RMS | E rel. MAE | E fine grain / converged's | "
            "AO RMS / mean occlusion | AO fine grain / converged's |\n"
            "|---|--:|--:|--:|--:|--:|--:|\n");
        for (const auto& name : options.scenes) {
            const deepgi::Scene scene = deepgi::load_scene(name);
            const deepgi::convergence::StillConvergence run =
                deepgi::convergence::measure_still_convergence(scene, settings, counts,
                                                               converged_taps, converged_frames);
            for (const deepgi::convergence::StillFigures& row : run.rows) {
                fmt::print(
                    "| {} | {} | {:.2f}% | {:.2f}% | {:.2f} ({:.2f}% / {:.2f}%) | {:.2f}% | "
                    "{:.2f} ({:.2f}% / {:.2f}%) |\n",
                    name, row.frames, 100.0 * row.e_rms, 100.0 * row.e_mae,
                    row.e_grain / run.converged_e_grain, 100.0 * row.e_grain,
                    100.0 * run.converged_e_grain, 100.0 * row.ao_rms,
                    row.ao_grain / run.converged_ao_grain, 100.0 * row.ao_grain,
                    100.0 * run.converged_ao_grain);
            }
            fmt::print("<!-- {}: {} flat pixels of {} -->\n", name, run.flat_pixels, run.pixels);
        }
        fmt::print("\nconverged: {} radiosity taps, {} still frames; device: {} | {}x{}\n",
                   converged_taps, converged_frames, deepgi::query_context_info().renderer,
                   options.width, options.height);
        return 0;
    });
}
