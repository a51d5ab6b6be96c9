#include "command_line.hpp"

#include "deepgi/errors.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/window_controls.hpp"

#include <fmt/format.h>
#include <spiral/fileio.hpp>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

namespace deepgi_app {

namespace {

std::string joined(const std::vector<std::string>& names) {
    std::string text;
    for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
    return text;
}

}  // namespace

std::string help_footer() {
    return fmt::format(
        "Subcommands (each has its own --help):\n"
        "  deepgi reference ...  ray-traced ambient visibility and one-bounce irradiance of a "
        "scene, as PFM images with PNG previews (docs/reference.md)\n"
        "  deepgi report ...     deep SAO speed against error for tap patterns, tap counts and "
        "layers, with figures (docs/report.md)\n"
        "\n"
        "Scenes (--scene, also for the subcommands):\n"
        "  {}  built-in scenes\n"
        "  {}  small scenes for measuring deep SAO against the reference "
        "(docs/reference.md)\n"
        "  FILE.gltf, FILE.glb  a glTF 2.0 file (docs/deepgi.md)\n"
        "\n"
        "Window keys:\n  {}\n{}\n--script FILE drives the window frame by frame "
        "(docs/deepgi.md, 'Interactive window').",
        joined(deepgi::builtin_scene_names()), joined(deepgi::reference_scene_names()),
        deepgi::movement_help(), deepgi::key_help_text());
}

int run_reporting_errors(std::string_view command, const std::function<int()>& work) {
    try {
        const int status = work();
        // What the command printed is an output too: a full disk or a closed
        // pipe must not end in exit 0.
        spiral::fileio::close_standard_output();
        return status;
    } catch (const deepgi::InputError& error) {
        spiral_apps::report_error(command, error.what());
        return exit_bad_input;
    } catch (const spiral::fileio::WriteError& error) {  // output path or full disk
        spiral_apps::report_error(command, error.what());
        return exit_bad_input;
    } catch (const std::filesystem::filesystem_error& error) {
        // A path given on the command line that cannot be examined or made (a
        // symlink loop, an over-long name, /proc): the input's fault. Named
        // without the library's "filesystem error: status:" prefix.
        const std::string path = error.path1().string();
        spiral_apps::report_error(
            command, path.empty() ? error.code().message()
                                  : fmt::format("'{}': {}", path, error.code().message()));
        return exit_bad_input;
    } catch (const std::exception& error) {
        spiral_apps::report_error(command, error.what());
        return 1;
    }
}

}  // namespace deepgi_app
