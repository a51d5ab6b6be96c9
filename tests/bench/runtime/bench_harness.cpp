#include "bench_harness.hpp"

#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

namespace deepgi::bench {

ShaderLoader with_sources_first(const ShaderLoader& loader, const std::filesystem::path& dir) {
    auto dirs = loader.include_dirs();
    dirs.insert(dirs.begin(), dir);
    return ShaderLoader(dirs);
}

void add_options(CLI::App& app, Options& options) {
    app.add_option("--size", options.size, "Image size WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--scenes", options.scenes, "Built-in scenes or glTF files, comma-separated")
        ->delimiter(',')
        ->capture_default_str();
    app.add_option("--frames", options.frames, "Timed frames per configuration (median reported)")
        ->capture_default_str();
    app.add_option("--warmup", options.warmup, "Untimed frames before the timed ones")
        ->capture_default_str();
    app.add_option("--timing", options.timing,
                   "cpu (CPU clock around glFinish, for llvmpipe) or gpu (GL timer queries)")
        ->capture_default_str();
    app.add_option("--set", options.set,
                   "NAME=VALUE: any numeric setting by the renderer's option name (deepgi "
                   "--help), e.g. blur-extent=0; repeatable");
}

void finish(Options& options) {
    const ImageSize size = parse_size("--size", options.size);
    options.width = size.width;
    options.height = size.height;
    if (options.frames < 1) throw InputError("--frames must be at least 1");
    if (options.warmup < 0) throw InputError("--warmup must be at least 0");
    if (options.scenes.empty()) throw InputError("--scenes needs at least one scene");
    options.timing_mode = parse_timing_mode("--timing", options.timing);
    if (options.timing_mode == TimingMode::automatic)
        throw InputError("--timing must be cpu or gpu: a benchmark says which clock it used");
    options.set_values.clear();
    for (const std::string& assignment : options.set) {
        const std::size_t equals = assignment.find('=');
        if (equals == std::string::npos)
            throw InputError(fmt::format("--set must be NAME=VALUE, got '{}'", assignment));
        const std::string name = assignment.substr(0, equals);
        const NumericSetting* row = find_numeric_setting(name);
        if (row == nullptr)
            throw InputError(fmt::format("--set: no setting named '{}' (deepgi --help)", name));
        options.set_values.emplace_back(
            row, parse_setting_value(*row, std::string_view(assignment).substr(equals + 1)));
    }
}

RenderSettings settings_for(const Options& options, RenderSettings settings) {
    settings.width = options.width;
    settings.height = options.height;
    settings.timing = options.timing_mode;
    for (const auto& [row, value] : options.set_values) row->set(settings, value);
    return settings;
}

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const std::size_t middle = values.size() / 2;
    return values.size() % 2 == 1 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

std::vector<PassMedians> time_alternated(const std::vector<Configuration>& configurations,
                                         const Options& options) {
    std::vector<std::map<std::string, std::vector<double>>> samples(configurations.size());
    for (int round = 0; round < options.warmup + options.frames; ++round) {
        for (std::size_t i = 0; i < configurations.size(); ++i) {
            Renderer& renderer = *configurations[i].renderer;
            renderer.render(configurations[i].camera);
            if (round < options.warmup) continue;
            double total = 0.0;
            for (const auto& timing : renderer.last_timings()) {
                samples[i][timing.pass].push_back(timing.milliseconds);
                total += timing.milliseconds;
            }
            samples[i]["total"].push_back(total);
        }
    }
    std::vector<PassMedians> medians(configurations.size());
    for (std::size_t i = 0; i < configurations.size(); ++i)
        for (auto& [pass, values] : samples[i]) medians[i][pass] = median(values);
    return medians;
}

std::string set_settings_note(const Options& options) {
    std::string note;
    for (const auto& [row, value] : options.set_values)
        note += accepts_auto(*row) && value == auto_length
                    ? fmt::format(" | {} = auto", row->name)
                    : fmt::format(" | {} = {}", row->name, value);
    return note;
}

std::string measured_on(const Renderer& renderer, const Options& options) {
    const ContextInfo info = query_context_info();
    return fmt::format(
        "device: {} ({}) | {}x{} | median of {} frames after {} warm-up frames{}", info.renderer,
        renderer.timing_uses_cpu_clock() ? "CPU clock around glFinish" : "GL timer queries",
        options.width, options.height, options.frames, options.warmup, set_settings_note(options));
}

int run(std::string_view name, const std::function<int()>& body) {
    try {
        const int status = body();
        if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
            fmt::print(stderr, "{}: error: could not write the table to stdout\n", name);
            return 1;
        }
        return status;
    } catch (const InputError& error) {
        fmt::print(stderr, "{}: error: {}\n", name, error.what());
        return 2;
    } catch (const std::exception& error) {
        fmt::print(stderr, "{}: error: {}\n", name, error.what());
        return 1;
    }
}

}  // namespace deepgi::bench
