// deepgi: the demo renderer's front end. Parses arguments, then either opens
// the interactive window or renders headless through EGL.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/frame_limits.hpp"
#include "deepgi/interactive.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/image_io.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/window_controls.hpp"
#include "command_line.hpp"
#include "help_formatter.hpp"
#include "reference_command.hpp"
#include "report_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <spiral/fileio.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using deepgi_app::parse_command_line;
using deepgi_app::run_reporting_errors;

namespace {

constexpr bool kAutoExposureByDefault = true;

struct Options {
    bool headless = false;
    bool hidden_window = false;
    std::string scene = "cornell";
    std::string size = "1280x720";
    int frames = 1;
    std::string output;
    std::string generator = "peel";
    std::string view = "final";
    std::string dump;
    bool ao_bias_given = false;
    // One value per row of deepgi::numeric_settings(), in table order, as
    // typed (a number, or "auto" for a length); only the options given on
    // the command line are applied, and lengths not given are auto.
    std::vector<std::string> numeric;
    std::vector<bool> numeric_given;
    std::string timing = "auto";
    bool camera_path = false;
    std::string camera;  // a file camera's name or index; empty for the scene's default
    bool print_timings = false;
    bool gl_debug = false;
    bool no_ao = false;
    bool no_radiosity = false;
    bool no_environment = false;
    bool no_reflections = false;
    std::string ao_method{deepgi::to_string(deepgi::AoSettings{}.method)};
    std::string radiosity_method{deepgi::to_string(deepgi::RadiositySettings{}.method)};
    std::vector<std::string> scene_limits;   // NAME=VALUE, see docs/hardening.md
    std::uint64_t max_gpu_mib = 4096;        // render-target estimate limit
    std::string script;                      // window: --script FILE
    std::string screenshot_directory = ".";  // window: where F12 writes
    std::string shaders;                     // --shaders DIR; empty: the build's only
};

// --shaders names a folder of edited shader copies that override the build's
// file by file. A folder holding none of the renderer's shader files is a
// mistake (a typo, the wrong level), not a request for the build's shaders.
void check_shader_folder(const std::string& folder) {
    if (folder.empty()) return;
    namespace fs = std::filesystem;
    std::error_code error;
    if (!fs::is_directory(folder, error))
        throw deepgi::InputError(fmt::format("--shaders {}: not a folder", folder));
    const fs::path sources =
        deepgi::ShaderLoader::from_build_configuration().include_dirs().front();
    for (const auto& entry : fs::directory_iterator(folder, error)) {
        if (entry.is_regular_file(error) && fs::is_regular_file(sources / entry.path().filename()))
            return;
    }
    throw deepgi::InputError(
        fmt::format("--shaders {}: holds none of the renderer's shader files", folder));
}

// Whether an option not given means `auto` on this command line: every
// length (it follows the scene), and the exposure (docs/deepgi.md,
// "Exposure", says why the command line and the library differ).
bool auto_unless_given(const deepgi::NumericSetting& row) {
    return deepgi::is_scene_length(row) || (row.auto_measured && kAutoExposureByDefault);
}

void check_output_path(const fs::path& output) {
    if (output == "-") return;  // the PNG goes to standard output
    std::string extension = output.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (extension != ".png")
        throw deepgi::InputError(fmt::format(
            "--output '{}': only PNG is written; the name must end in .png", output.string()));
    const fs::path parent = output.has_parent_path() ? output.parent_path() : fs::path(".");
    if (!fs::is_directory(parent)) {
        throw deepgi::InputError(fmt::format("--output '{}': directory '{}' does not exist",
                                             output.string(), parent.string()));
    }
    if (fs::is_directory(output))
        throw deepgi::InputError(fmt::format("--output '{}' is a directory", output.string()));
}

// Parses text into settings; every check is deepgi::validate()'s.
deepgi::RenderSettings settings_from(const Options& options) {
    deepgi::RenderSettings settings;
    const deepgi::ImageSize size = deepgi::parse_size("--size", options.size);
    settings.width = size.width;
    settings.height = size.height;
    settings.generator = deepgi::parse_generator("--generator", options.generator);
    settings.view = deepgi::parse_debug_view("--view", options.view);
    settings.timing = deepgi::parse_timing_mode("--timing", options.timing);
    const auto rows = deepgi::numeric_settings();
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (!options.numeric_given[i]) {
            // Lengths follow the scene unless given (docs/deepgi.md, "Scene scale").
            if (auto_unless_given(rows[i])) rows[i].set(settings, deepgi::auto_length);
            continue;
        }
        // Checked as typed, before the float conversion could round 2.5 to
        // a whole number.
        rows[i].set(settings, deepgi::parse_setting_value(rows[i], options.numeric[i]));
    }
    settings.ao.method = deepgi::parse_ao_method("--ao-method", options.ao_method);
    if (!options.ao_bias_given) settings.ao.bias = deepgi::default_ao_bias(settings.ao.method);
    settings.radiosity.method =
        deepgi::parse_radiosity_method("--radiosity-method", options.radiosity_method);
    settings.gl_debug = options.gl_debug;
    settings.ao.enabled = !options.no_ao;
    settings.radiosity.enabled = !options.no_radiosity;
    settings.environment = !options.no_environment;
    settings.reflection.enabled = !options.no_reflections;
    deepgi::validate(settings);
    return settings;
}

int run_headless(const Options& options, const deepgi::RenderSettings& settings) {
    if (options.output.empty()) throw deepgi::InputError("--headless needs --output FILE.png");
    if (options.frames < 1) throw deepgi::InputError("--frames must be at least 1");
    check_output_path(options.output);
    // Both outputs are checked before any work, so a bad --dump cannot fail
    // after the PNG was written (docs/hardening.md: output paths).
    spiral::fileio::check_file_target(options.output);
    if (!options.dump.empty()) spiral::fileio::check_directory_target(options.dump, ".pfm");
    if (options.hidden_window && (!options.dump.empty() || options.print_timings)) {
        throw deepgi::InputError(
            "--hidden-window writes only the PNG (no --dump or --print-timings)");
    }
    deepgi::SceneLimits limits;
    for (const auto& assignment : options.scene_limits) deepgi::set_scene_limit(limits, assignment);
    deepgi::Scene scene = deepgi::load_scene(options.scene, limits);
    scene.default_camera = deepgi::select_camera(scene, options.camera);
    if (options.hidden_window) {
        deepgi::render_hidden_window(scene, settings, options.frames, options.camera_path,
                                     options.output, options.shaders);
        return 0;
    }
    deepgi::HeadlessContext context;
    deepgi::Renderer renderer(scene, settings,
                              deepgi::ShaderLoader::from_build_configuration(options.shaders));
    // Information goes to standard output, unless the PNG does (--output -,
    // or a path that is standard output, such as a link to /dev/stdout).
    struct stat stdout_status {
    }, output_status{};
    const bool png_on_stdout =
        options.output == "-" || (::fstat(STDOUT_FILENO, &stdout_status) == 0 &&
                                  ::stat(options.output.c_str(), &output_status) == 0 &&
                                  stdout_status.st_dev == output_status.st_dev &&
                                  stdout_status.st_ino == output_status.st_ino);
    for (const std::string& line : deepgi::describe_auto_lengths(
             settings, renderer.settings_in_use(), deepgi::scene_scale(scene)))
        fmt::print(png_on_stdout ? stderr : stdout, "scene scale: {}\n", line);
    // A labelled bar for long runs, only where someone watches.
    const bool show_progress = options.frames > 1 && isatty(fileno(stderr)) != 0;
    for (int frame = 0; frame < options.frames; ++frame) {
        // The next frame's camera too, for the delay generator: the headless
        // run knows its whole path, so it runs one frame behind it at no cost.
        if (options.camera_path)
            renderer.render(deepgi::camera_on_path(scene.camera_path, frame),
                            deepgi::camera_on_path(scene.camera_path, frame + 1));
        else
            renderer.render(scene.default_camera, scene.default_camera);
        if (show_progress) {
            const int width = 40, filled = width * (frame + 1) / options.frames;
            fmt::print(stderr, "\rdeepgi: frames rendered [{:<{}}] {}/{}",
                       std::string(std::size_t(filled), '#'), width, frame + 1, options.frames);
            if (frame + 1 == options.frames) fmt::print(stderr, "\n");
            std::fflush(stderr);
        }
    }
    // The PNG is committed only after the dump is complete: a failed dump
    // leaves neither.
    const auto png =
        deepgi::encode_png(settings.width, settings.height, renderer.read_output_rgba8());
    spiral::fileio::AtomicFile output(options.output);
    output.write(png.data(), png.size());
    if (!options.dump.empty()) renderer.dump_pass_outputs(options.dump);
    output.commit();
    if (options.print_timings) {
        const auto info = deepgi::query_context_info();
        fmt::print(
            "renderer: {} ({})\n", info.renderer,
            renderer.timing_uses_cpu_clock() ? "CPU clock around glFinish" : "GL timer queries");
        for (const auto& timing : renderer.last_timings())
            fmt::print("{:<14} {:8.3f} ms\n", timing.pass, timing.milliseconds);
        double total = 0.0;
        for (const auto& timing : renderer.last_timings()) total += timing.milliseconds;
        fmt::print("{:<14} {:8.3f} ms\n", "total", total);
        // What the frame_statistics pass measured (docs/deepgi.md, "Exposure").
        const deepgi::FrameStatistics& statistics = renderer.frame_statistics();
        fmt::print("exposure in use {:.4g} ({}; log-average luminance {:.4g})\n",
                   statistics.exposure, settings.exposure == deepgi::auto_length ? "auto" : "set",
                   statistics.log_average_luminance);
        for (int layer = 0; layer < 2; ++layer) {
            const deepgi::DepthRange& range = statistics.depth_ranges[std::size_t(layer)];
            fmt::print("depth range of layer {}: {:.4g} to {:.4g}\n", layer, range.near_depth,
                       range.far_depth);
        }
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    // Subcommands take over the whole command line.
    if (argc > 1 && std::string(argv[1]) == "reference")
        return deepgi_app::run_reference_command(argc, argv);
    if (argc > 1 && std::string(argv[1]) == "report")
        return deepgi_app::run_report_command(argc, argv);
    Options options;
    CLI::App app{
        "deepgi: deep G-buffer demo renderer (OpenGL 4.5). Without --headless it opens an "
        "interactive window (GLFW + Dear ImGui panel that edits every setting below and the "
        "light live); with --headless it renders through EGL and writes --output."};
    // --help shows every default, in words (help_formatter.hpp).
    app.option_defaults()->always_capture_default();
    spiral_apps::use_help_formatter(app);
    app.footer(deepgi_app::help_footer());
    app.add_flag("--headless", options.headless,
                 "Render without a window (EGL) and write --output");
    app.add_flag("--hidden-window", options.hidden_window,
                 "With --headless: render in a hidden GLFW window instead of EGL (needs an X "
                 "server, e.g. xvfb-run)");
    app.add_option("--scene", options.scene,
                   "A built-in scene (listed at the end) or a .gltf/.glb file");
    app.add_option("--scene-limit", options.scene_limits,
                   "Raise a scene file limit (also for files dropped onto the window), NAME=VALUE: "
                   "json-depth, node-visits, triangles, instances, geometry-bytes, "
                   "load-seconds, texture-side, texture-bytes, file-bytes (docs/hardening.md)")
        ->default_str("the limits in docs/hardening.md");
    app.add_option("--size", options.size,
                   fmt::format("Image size WIDTHxHEIGHT in pixels (1 to {} per side)",
                               deepgi::limits::max_image_side))
        ->default_str("1280x720 pixels");
    app.add_option("--max-gpu-memory", options.max_gpu_mib,
                   "Refuse a --size/--guard-band whose render targets need more than this "
                   "many MiB (1 to 2^40)")
        ->check(CLI::Range(std::uint64_t(1), std::uint64_t(1) << 40))
        ->default_str("4096 MiB");
    app.add_option("--frames", options.frames,
                   "Frames to render before writing the output (headless)")
        ->default_str("1 frame");
    app.add_option("--output", options.output, "PNG file to write (headless)")
        ->default_str("none; --headless needs one");
    app.add_option("--generator", options.generator,
                   "Deep G-buffer generator: " + deepgi::enum_name_list<deepgi::Generator>() +
                       " (peel: two passes; previous, reproject: one pass against the last "
                       "frame; delay, predict: one pass against a third depth layer drawn "
                       "with the next frame's camera, known or extrapolated)");
    app.add_option("--view", options.view,
                   "Image to show: " + deepgi::enum_name_list<deepgi::DebugView>());
    app.add_option("--dump", options.dump,
                   "Directory for 32-bit float PFM images of every pass output (headless)")
        ->default_str("none, no dump");
    app.add_option("--timing", options.timing,
                   "Pass timing: " + deepgi::enum_name_list<deepgi::TimingMode>() +
                       " (cpu: glFinish and a CPU clock; gpu: timer queries)");
    app.add_option("--camera", options.camera,
                   "View through the glTF file's camera of this name or index, or through "
                   "pose:X,Y,Z,YAW,PITCH,FOVY,NEAR (degrees; what a window screenshot's "
                   "camera.txt holds); in the window, R resets to it")
        ->default_str("the file's first perspective camera, else a fitted view");
    app.add_flag("--camera-path", options.camera_path,
                 "Move along the scene's camera path, one step per frame");
    app.add_flag("--print-timings", options.print_timings,
                 "Print the last frame's per-pass milliseconds");
    app.add_option("--script", options.script,
                   "Window only: run the window from a script of per-frame commands (set, key, "
                   "hold, drag, resize, capture, screenshot, drop, quit; docs/deepgi.md)")
        ->default_str("none");
    app.add_option("--screenshot-dir", options.screenshot_directory,
                   "Window only: F12 writes a dated folder (PNG + pass PFMs) in this directory")
        ->default_str("the current directory");
    app.add_option("--shaders", options.shaders,
                   "A folder of edited shader copies, searched before the build's shaders: "
                   "try a shader change without editing the sources")
        ->default_str("none");
    app.add_flag("--gl-debug", options.gl_debug,
                 "Turn GL errors into an error that names the pass (KHR_debug callback)");
    // Which indirect terms compose adds (docs/radiosity.md, "What each part adds").
    app.add_flag("--no-ao", options.no_ao, "Compose without the deep SAO (visibility 1)");
    app.add_flag("--no-radiosity", options.no_radiosity,
                 "Compose without the deep radiosity (the environment term fills everywhere)");
    app.add_flag("--no-environment", options.no_environment,
                 "Compose without the environment term (with --no-radiosity --no-ao: direct "
                 "light and emissive only)");
    app.add_flag("--no-reflections", options.no_reflections,
                 "Trace no mirror reflections (mirror materials are shaded as diffuse)");
    // Deep SAO (docs/deep-sao.md).
    app.add_option("--ao-method", options.ao_method,
                   fmt::format("Deep SAO estimator: {} (spiral-thick unions the "
                               "directions hidden by each spiral tap's solid, front to back "
                               "face; march casts the reference's rays through the same "
                               "solids, about 4x the cost of the solid angle; solid-angle "
                               "is the reference's integral over the seen surface on the "
                               "spiral taps; published is 1 - sqrt(...); gtao and bitmask "
                               "march --ao-slices screen-space slices of --ao-steps samples: "
                               "gtao's horizons, or bitmask's 32 sectors hidden by samples "
                               "--ao-thickness thick)",
                               deepgi::enum_name_list<deepgi::AoMethod>()))
        ->capture_default_str();

    // Deep radiosity (docs/radiosity.md).
    app.add_option("--radiosity-method", options.radiosity_method,
                   fmt::format("Deep radiosity estimator: {} (area is the reference's "
                               "irradiance integral, published is 2 pi / M * sum B cos)",
                               deepgi::enum_name_list<deepgi::RadiosityMethod>()))
        ->capture_default_str();

    // Every numeric setting from its row: help, unit, limits and default.
    {
        const deepgi::RenderSettings defaults;
        const auto rows = deepgi::numeric_settings();
        options.numeric.resize(rows.size());
        options.numeric_given.assign(rows.size(), false);
        for (std::size_t i = 0; i < rows.size(); ++i) {
            const deepgi::NumericSetting& row = rows[i];
            options.numeric[i] =
                auto_unless_given(row) ? std::string("auto") : fmt::format("{}", row.get(defaults));
            app.add_option(fmt::format("--{}", row.name), options.numeric[i],
                           fmt::format("{} ({})", row.help, deepgi::describe_limits(row)))
                ->type_name(row.integer                 ? "INT"
                            : deepgi::accepts_auto(row) ? "FLOAT|auto"
                                                        : "FLOAT")
                ->default_str(
                    deepgi::is_scene_length(row) ? std::string(spiral_apps::scene_length_default)
                    : auto_unless_given(row)     ? std::string("auto, from the frame's luminance")
                                             : spiral_apps::with_unit(row.get(defaults), row.unit))
                ->group(row.group == "frame"        ? "Frame"
                        : row.group == "ao"         ? "Deep SAO"
                        : row.group == "radiosity"  ? "Deep radiosity"
                        : row.group == "reflection" ? "Mirror reflections"
                                                    : "Bilateral blur");
        }
    }
    if (const auto status = parse_command_line(app, argc, argv, "deepgi")) return *status;
    options.ao_bias_given = app.count("--ao-bias") > 0;
    for (std::size_t i = 0; i < options.numeric.size(); ++i)
        options.numeric_given[i] =
            app.count(fmt::format("--{}", deepgi::numeric_settings()[i].name)) > 0;

    return run_reporting_errors("deepgi", [&] {
        const deepgi::RenderSettings settings = settings_from(options);
        check_shader_folder(options.shaders);
        deepgi::check_frame_limits(settings, options.max_gpu_mib << 20);
        if (options.headless) {
            for (const char* name : {"--script", "--screenshot-dir"})
                if (app.count(name) > 0)
                    throw deepgi::InputError(
                        fmt::format("{} only applies to the window (leave out --headless)", name));
            return run_headless(options, settings);
        }
        if (options.hidden_window) throw deepgi::InputError("--hidden-window needs --headless");
        // The window would silently ignore these; say so instead.
        std::string headless_only;
        for (const char* name : {"--output", "--dump", "--frames", "--camera-path"})
            if (app.count(name) > 0)
                headless_only += std::string(headless_only.empty() ? "" : ", ") + name;
        if (!headless_only.empty())
            throw deepgi::InputError(
                fmt::format("{} only apply with --headless (leaving out --headless "
                            "opens a window)",
                            headless_only));
        deepgi::WindowOptions window;
        window.scene = options.scene;
        for (const auto& assignment : options.scene_limits)
            deepgi::set_scene_limit(window.scene_limits, assignment);
        window.camera = options.camera;
        window.script = options.script;
        window.screenshot_directory = options.screenshot_directory;
        window.shaders = options.shaders;
        try {
            return deepgi::run_interactive(window, settings);
        } catch (const deepgi::NoDisplayError& error) {
            throw deepgi::GraphicsError(
                fmt::format("{}; --headless --output FILE.png renders without one", error.what()));
        }
    });
}
