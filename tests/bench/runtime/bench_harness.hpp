#pragma once
// What every runtime benchmark shares: the flags (--size --scenes --frames
// --warmup --timing --set), the alternated timing of several configurations in one
// run, medians, and the line that says what the figures were measured on.
// Alternating matters on a shared, noisy machine: each round renders one
// frame of every configuration in turn, so a slow spell costs all of them.
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/settings.hpp"
#include "deepgi/shader_loader.hpp"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace deepgi::bench {

struct Options {
    std::string size = "1280x720";
    std::vector<std::string> scenes;
    int frames = 7;  // timed frames per configuration (the median is reported)
    int warmup = 2;  // untimed frames first, so single-pass generators have a previous frame
    std::string timing = "cpu";  // cpu: CPU clock around glFinish; gpu: GL timer queries
    // --set NAME=VALUE, repeatable: any numeric setting by its row (the
    // renderer's command-line name, e.g. blur-extent=0), so a benchmark runs
    // at a setting it has no flag of its own for.
    std::vector<std::string> set;
    // Filled by finish():
    int width = 0;
    int height = 0;
    TimingMode timing_mode = TimingMode::cpu;
    std::vector<std::pair<const NumericSetting*, float>> set_values;
};

// `loader` with `dir` searched first, so that the shader sources in it and
// the includes beside them win over the loader's own (--baseline-shaders:
// the shaders before a change, timed against today's in one alternation).
ShaderLoader with_sources_first(const ShaderLoader& loader, const std::filesystem::path& dir);

// Adds the shared flags; `options` holds each benchmark's defaults.
void add_options(CLI::App& app, Options& options);
// Checks the flags after parsing and fills width, height and timing_mode;
// throws InputError with one line naming the flag.
void finish(Options& options);
// `base` at the options' size and timing mode, with the --set values on top.
// A benchmark's own flags and configurations are applied after it, so they win.
RenderSettings settings_for(const Options& options, RenderSettings base = {});

double median(std::vector<double> values);

// Per-pass median milliseconds (and "total") of one configuration.
using PassMedians = std::map<std::string, double>;

// One configuration of an alternated run: its renderer and camera.
struct Configuration {
    Renderer* renderer = nullptr;
    Camera camera;
};
// Renders options.warmup then options.frames rounds; each round renders one
// frame of every configuration in turn. Returns each configuration's medians.
std::vector<PassMedians> time_alternated(const std::vector<Configuration>& configurations,
                                         const Options& options);

// " | NAME = VALUE" for each --set value, or "": part of what a table says it
// was measured with.
std::string set_settings_note(const Options& options);
// "device: <renderer> (<clock>) | WxH | median of N frames after W warm-up
// frames", then set_settings_note().
std::string measured_on(const Renderer& renderer, const Options& options);

// Runs a benchmark's body: InputError is exit 2 with one line, anything else
// exit 1, both prefixed with the benchmark's name.
int run(std::string_view name, const std::function<int()>& body);

}  // namespace deepgi::bench
