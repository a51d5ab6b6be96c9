// `deepgi report`: parses the options, runs deepgi::report::run_report in a
// headless context, then has scripts/plot_report.py draw the figures and
// write summary.md from the CSV (docs/report.md).
#include "report_command.hpp"

#include "deepgi/context.hpp"
#include "command_line.hpp"
#include "help_formatter.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/settings.hpp"
#include "deepgi/report.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace deepgi_app {
namespace {

struct CommandOptions {
    deepgi::report::ReportOptions report;
    std::string size = "320x180";
    std::string output;
    bool plots = true;
    bool no_plots = false;
    bool no_reflections = false;
    std::string python = "/usr/bin/python3";
    std::string plot_script = DEEPGI_PLOT_REPORT_SCRIPT;
};

// Runs `python script dir` without a shell (no quoting of paths), returning
// its exit status, or -1 when it could not be started.
int run_plot_script(const std::string& python, const std::string& script,
                    const std::string& directory) {
    const pid_t child = fork();
    if (child < 0) return -1;
    if (child == 0) {
        std::vector<char*> args = {const_cast<char*>(python.c_str()),
                                   const_cast<char*>(script.c_str()),
                                   const_cast<char*>(directory.c_str()), nullptr};
        execv(python.c_str(), args.data());
        _exit(127);
    }
    int status = 0;
    if (waitpid(child, &status, 0) < 0) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int run(CommandOptions& options) {
    const deepgi::ImageSize size = deepgi::parse_size("--size", options.size);
    options.report.width = size.width;
    options.report.height = size.height;
    options.report.output = options.output;
    deepgi::report::validate(options.report);
    if (options.plots && access(options.plot_script.c_str(), R_OK) != 0)
        throw deepgi::InputError(fmt::format(
            "--plot-script '{}' cannot be read (or pass --no-plots)", options.plot_script));

    options.report.log = [](const std::string& line) {
        fmt::print("{}\n", line);
        std::fflush(stdout);
    };
    // Labelled progress where someone watches; logs stay as they were.
    if (isatty(fileno(stderr))) {
        options.report.progress = [](int done, int total, const std::string& step) {
            fmt::print(stderr, "deepgi report: steps done {}/{}, now: {}\n", done, total, step);
            std::fflush(stderr);
        };
    }
    deepgi::HeadlessContext context;
    const auto result = deepgi::report::run_report(options.report);
    fmt::print("report: {} rows in {:.0f} s, written to {}\n", result.rows.size(),
               result.info.seconds, options.output);
    if (!options.plots) return 0;
    const int status = run_plot_script(options.python, options.plot_script, options.output);
    if (status != 0) {
        fmt::print(stderr, "deepgi report: error: {} {} exited with status {}\n", options.python,
                   options.plot_script, status);
        return 1;
    }
    return 0;
}

}  // namespace

int run_report_command(int argc, char** argv) {
    CommandOptions options;
    deepgi::report::ReportOptions& report = options.report;
    CLI::App app{"deepgi report: deep SAO speed against error for tap patterns, counts, layers"};
    app.option_defaults()->always_capture_default();
    spiral_apps::use_help_formatter(app);
    auto listed = [](const auto& values) {
        std::string text;
        for (const auto& value : values)
            text += fmt::format("{}{}", text.empty() ? "" : ",", value);
        return text;
    };
    app.add_option("--scenes", report.scenes,
                   "Scenes, comma-separated (built-in names, listed by deepgi --help, or glTF "
                   "files)")
        ->delimiter(',')
        ->default_str(listed(report.scenes));
    app.add_option("--taps", report.taps, "Tap counts, comma-separated")
        ->delimiter(',')
        ->default_str(listed(report.taps));
    app.add_option("--patterns", report.patterns,
                   "Tap patterns, comma-separated: optimal, tau1, golden, m2, m4, m8")
        ->delimiter(',')
        ->default_str(listed(report.patterns));
    app.add_option("--layers", report.layers, "G-buffer layer counts, comma-separated (1, 2)")
        ->delimiter(',')
        ->default_str(listed(report.layers));
    std::vector<std::string> ao_methods;
    app.add_option("--ao-methods", ao_methods,
                   fmt::format("Deep SAO estimators, comma-separated ({}); the first compares "
                               "the patterns",
                               deepgi::enum_name_list<deepgi::AoMethod>()))
        ->delimiter(',')
        ->default_str("solid-angle,published,march");
    std::vector<std::string> slice_costs;
    app.add_option("--slice-costs", slice_costs,
                   "gtao and bitmask: the SLICESxSTEPS costs each runs at, comma-separated "
                   "(--ao-slices x --ao-steps)")
        ->delimiter(',')
        ->default_str("1x4,2x8,4x8");
    app.add_option("--flicker-frames", report.estimators.flicker_frames,
                   "Frames at a still camera and along the camera path whose second half's "
                   "frame-to-frame change flicker.csv holds (0: skip; else 4 to 256)")
        ->default_str(fmt::format("{} frames", report.estimators.flicker_frames));
    app.add_option("--size", options.size, "Viewport WIDTHxHEIGHT in pixels (guard band added)")
        ->default_str(options.size + " pixels");
    app.add_option("--rays", report.rays,
                   "Reference rays per pixel; 0: as many as `deepgi reference` traces for its "
                   "standard-error targets")
        ->default_str(fmt::format("{} rays", report.rays));
    app.add_option("--output", options.output, "Directory for the report")
        ->default_str("none; report needs one");
    app.add_option("--converged-taps", report.converged_taps,
                   "Taps of the converged screen-space result")
        ->default_str(fmt::format("{} taps", report.converged_taps));
    app.add_option("--warmup", report.warmup, "Untimed frames before the timed ones")
        ->default_str(fmt::format("{} frame", report.warmup));
    app.add_option("--frames", report.frames,
                   "Timed frames (the median is reported); the accumulated errors are read after "
                   "9 static frames either way")
        ->default_str(fmt::format("{} frames", report.frames));
    app.add_option("--threads", report.threads, "Reference threads (0: all hardware threads)")
        ->default_str("0, all hardware threads");
    app.add_option("--seed", report.seed, "Reference random seed");
    app.add_option("--image-taps", report.image_taps,
                   "Tap count of the per-scene truth/estimate images (nearest in --taps)")
        ->default_str(fmt::format("{} taps", report.image_taps));
    app.add_option("--repeats", report.repeats,
                   "Renders of every row, each with the temporal sequence started elsewhere; "
                   "their spread is the run's noise, and no difference within it is ranked")
        ->default_str(fmt::format("{} renders", report.repeats));
    app.add_option("--radiosity-frames", report.radiosity_frames,
                   "Still frames whose running mean of the radiosity the per-scene radiosity "
                   "section compares with the truths, at the renderer's radiosity tap count "
                   "(the nearest in --taps); 0: skip, and judge after the 9-frame cycle")
        ->default_str(fmt::format("{} frames", report.radiosity_frames));
    std::string lengths = "library";
    app.add_option("--lengths", lengths,
                   "library: every length at the library's metres (AO radius 0.5, radiosity "
                   "radius 1); auto: at the command line's defaults, a fraction of each "
                   "scene's size")
        ->check(CLI::IsMember({"library", "auto"}))
        ->default_str("library");
    app.add_flag("--stability", report.stability,
                 "Also render the numerical hard cases (stability.csv); off unless given");
    app.add_flag("--float-check", report.float_check,
                 "Also compare the exact tau search with a double-precision one "
                 "(float_vs_exact.csv); off unless given");
    auto* float_max_n =
        app.add_option("--float-max-n", report.float_max_n, "With --float-check: compare n = 1..N")
            ->default_str(fmt::format("n = {}", report.float_max_n));
    app.add_option("--reflection-steps", report.reflections.steps,
                   "Reflection step counts of the mirror rows, comma-separated")
        ->delimiter(',')
        ->default_str(listed(report.reflections.steps));
    app.add_option("--reflection-frames", report.reflections.frames,
                   "Still frames per mirror configuration (the filtered radiance's mean; the "
                   "timed ones follow --warmup)")
        ->default_str(fmt::format("{} frames", report.reflections.frames));
    app.add_option("--ties-from", report.ties.verdicts_from,
                   "A tie_error_study --verdicts-csv file: ties.csv and the summary then say "
                   "whether each pick samples worse than the best other tie beyond its spread");
    app.add_flag("--no-reflections", options.no_reflections,
                 "Skip the mirror rows (reflections.csv)");
    app.add_flag("--no-plots", options.no_plots, "Skip the matplotlib figures and summary.md");
    app.add_option("--python", options.python, "Python interpreter with matplotlib");
    app.add_option("--plot-script", options.plot_script,
                   "The plotting script (scripts/plot_report.py of the source tree)");
    // A single-valued option given twice takes the last value, so that
    // scripts/report.sh's extra flags override its configuration.
    for (CLI::Option* option : app.get_options()) {
        if (option->get_items_expected_max() == 1)
            option->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    }
    if (const auto status = parse_command_line(app, argc - 1, argv + 1, "deepgi report"))
        return *status;
    report.reflections.enabled = !options.no_reflections;
    report.scene_lengths = lengths == "auto";
    options.plots = !options.no_plots;
    return run_reporting_errors("deepgi report", [&] {
        if (float_max_n->count() > 0 && !report.float_check)
            throw deepgi::InputError("--float-max-n applies only with --float-check");
        if (!ao_methods.empty()) {
            report.ao_methods.clear();
            for (const std::string& name : ao_methods)
                report.ao_methods.push_back(deepgi::parse_ao_method("--ao-methods", name));
        }
        if (!slice_costs.empty()) {
            report.estimators.slice_costs.clear();
            for (const std::string& text : slice_costs)
                report.estimators.slice_costs.push_back(
                    deepgi::report::parse_slice_cost("--slice-costs", text));
        }
        return run(options);
    });
}

}  // namespace deepgi_app
