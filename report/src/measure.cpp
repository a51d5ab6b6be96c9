// The report's run: sets up the shared configuration (frame size, the
// scratch folder of tap headers, the image configuration), runs every
// scene's rows (scene_rows.cpp), flicker rows (estimators.cpp) and mirror
// rows (reflections.cpp), the side tables, and writes the files; the tables
// are formatted by format.cpp.
#include "estimators.hpp"
#include "scene_rows.hpp"
#include "deepgi/context.hpp"
#include "deepgi/report.hpp"
#include "deepgi/settings.hpp"

#include <spiral/fileio.hpp>

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace deepgi::report {

namespace {

class ScratchFolder {
public:
    ScratchFolder() {
        static std::atomic<int> counter{0};
        path_ =
            fs::temp_directory_path() / fmt::format("deepgi-report-{}-{}", ::getpid(), counter++);
        fs::create_directories(path_);
    }
    ~ScratchFolder() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

// The build's shader folders with the scratch folder searched right after
// the top-level shader folder, so its headers win over the generated ones.
ShaderLoader loader_with_override(const fs::path& folder) {
    auto dirs = ShaderLoader::from_build_configuration().include_dirs();
    dirs.insert(dirs.begin() + 1, folder);
    return ShaderLoader(dirs);
}

void write_text(const fs::path& path, std::string_view text) {
    spiral::fileio::AtomicFile file(path);
    file.write(text);
    file.commit();
}

// Writes the AO and radiosity tap headers for a pattern at n taps.
void write_headers(const fs::path& folder, const std::string& pattern, int n) {
    const Turns turns = pattern_turns(pattern, n);
    const auto taps = spiral::codegen::spiral_taps(n, turns.p, turns.m);
    const std::string what = fmt::format("{}, {} taps, {}/{} turns", pattern, n, turns.p, turns.m);
    write_text(folder / "ao_taps.glsl", format_taps_header("AO", taps, turns, what));
    write_text(folder / "radiosity_taps.glsl", format_taps_header("RADIOSITY", taps, turns, what));
}

int nearest(const std::vector<int>& values, int target) {
    int best = values.front();
    for (int v : values) {
        if (std::abs(v - target) < std::abs(best - target)) best = v;
    }
    return best;
}

// The tables beside the rows: the numerical hard cases and the float search
// against the exact one, each written or, when skipped, removed so that a
// table from an earlier run into the same folder is not read as this run's.
void measure_side_tables(const ReportOptions& options, ReportResult& result,
                         const std::function<void(const std::string&)>& log,
                         const std::function<void(const std::string&)>& step) {
    write_tie_table(options.output, options.taps, options.ties);  // exact: no rendering
    if (options.stability) {
        step("stability cases");
        const auto stability_start = std::chrono::steady_clock::now();
        result.stability =
            run_stability_cases(hard_cases::Parameters{}, options.ao_methods, options.log);
        const auto passing = std::count_if(result.stability.begin(), result.stability.end(),
                                           [](const StabilityRow& row) { return row.pass; });
        log(fmt::format(
            "stability: {} of {} checks pass, {:.1f} s", passing, result.stability.size(),
            std::chrono::duration<double>(std::chrono::steady_clock::now() - stability_start)
                .count()));
        write_text(options.output / "stability.csv", format_stability_csv(result.stability));
    } else {
        fs::remove(options.output / "stability.csv");
    }
    if (options.float_check) {
        step("float against exact search");
        const auto float_start = std::chrono::steady_clock::now();
        result.float_choices =
            spiral_float::compare_float_search(options.float_max_n, options.threads);
        const auto differing =
            std::count_if(result.float_choices.begin(), result.float_choices.end(),
                          [](const spiral_float::Choice& c) { return c.differs(); });
        log(fmt::format(
            "float vs exact: double picks another tau at {} of n = 1..{}, {:.1f} s", differing,
            options.float_max_n,
            std::chrono::duration<double>(std::chrono::steady_clock::now() - float_start).count()));
        write_text(options.output / "float_vs_exact.csv", format_float_csv(result.float_choices));
    } else {
        fs::remove(options.output / "float_vs_exact.csv");
    }
}

}  // namespace

ReportResult run_report(const ReportOptions& options) {
    validate(options);
    const auto start = std::chrono::steady_clock::now();
    auto log = [&](const std::string& line) {
        if (options.log) options.log(line);
    };

    RenderSettings settings;
    settings.width = options.width;
    settings.height = options.height;
    // One bounce: the truth is one-bounce irradiance, and after the cycle of
    // static frames the history would otherwise also hold the bounces that
    // rho_prop feeds back. A first frame has no history, and the gather does
    // the same work either way, so no other column moves.
    settings.radiosity.rho_prop = 0.0f;
    deepgi::validate(settings);
    const int guard = frame_layout(settings).guard;

    ScratchFolder headers;
    const ShaderLoader loader = loader_with_override(headers.path());
    const int image_taps = nearest(options.taps, options.image_taps);
    // The renderer's default radiosity tap count (the CMake option
    // RADIOSITY_TAPS), or the run's nearest.
    const int radiosity_taps = nearest(options.taps, DEEPGI_REPORT_RADIOSITY_TAPS);
    const std::string image_pattern = std::find(options.patterns.begin(), options.patterns.end(),
                                                options.image_pattern) != options.patterns.end()
                                          ? options.image_pattern
                                          : options.patterns.front();
    const int image_layers = *std::max_element(options.layers.begin(), options.layers.end());
    const SliceCost image_cost = image_slice_cost(options.estimators);

    fs::create_directories(options.output / "images");
    write_text(options.output / "discrepancy.csv", format_discrepancy_csv(options.patterns, 64));

    ReportResult result;
    const ContextInfo context = query_context_info();
    result.info.renderer = context.renderer;
    result.info.vendor = context.vendor;
    result.info.width = options.width;
    result.info.height = options.height;
    result.info.guard = guard;
    result.info.rays = options.rays;
    result.info.converged_taps = options.converged_taps;
    result.info.warmup = options.warmup;
    result.info.frames = options.frames;
    result.info.image_pattern = image_pattern;
    result.info.image_taps = image_taps;
    result.info.repeats = options.repeats;
    result.info.lengths = options.scene_lengths ? "auto" : "library";
    result.info.radiosity_frames = options.radiosity_frames;
    result.info.radiosity_taps = options.radiosity_frames > 0 ? radiosity_taps : 0;

    // Progress: one step per scene, then the side tables that run.
    const int steps =
        int(options.scenes.size()) + (options.stability ? 1 : 0) + (options.float_check ? 1 : 0);
    int steps_done = 0;
    auto step = [&](const std::string& name) {
        if (options.progress) options.progress(steps_done, steps, name);
        ++steps_done;
    };
    for (const std::string& scene_name : options.scenes) {
        step("scene " + scene_name);
        const Scene scene = load_scene(scene_name);
        // The lengths (scene units) every part of the scene's rows uses, the
        // truths' too.
        const RenderSettings scene_settings =
            options.scene_lengths
                ? resolve_auto_lengths(with_auto_lengths(settings), scene_scale(scene))
                : settings;
        const SceneSetup setup{
            .scene = scene,
            .scene_name = scene_name,
            .settings = scene_settings,
            .loader = loader,
            .write_headers = [&](const std::string& pattern,
                                 int n) { write_headers(headers.path(), pattern, n); },
            .image_pattern = image_pattern,
            .image_taps = image_taps,
            .image_layers = image_layers,
            .image_cost = image_cost,
            .radiosity_taps = radiosity_taps,
            .converged_taps = options.converged_taps};
        measure_scene_rows(setup, options, result, log);
        measure_flicker_rows(setup, options, result.flicker, log);
        for (ReflectionRow& row : measure_reflection_rows(
                 scene_name, scene, scene_settings, options.reflections, options.layers,
                 options.rays, options.seed, options.threads, options.warmup, options.log))
            result.reflections.push_back(std::move(row));
    }

    measure_side_tables(options, result, log, step);

    result.info.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    write_reflection_table(options.output, options.reflections.enabled, result.reflections);
    write_text(options.output / "report.csv", format_csv(result.rows));
    if (options.estimators.flicker_frames > 0)
        write_text(options.output / "flicker.csv", format_flicker_csv(result.flicker));
    else
        fs::remove(options.output / "flicker.csv");
    write_text(options.output / "report.json",
               format_json(result.rows, result.info, result.stability, result.float_choices));
    return result;
}

}  // namespace deepgi::report
