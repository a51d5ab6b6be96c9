#include "command_line.hpp"

#include "../strict_numbers.hpp"
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

// The contract is one line: a name with a newline in it (a scene, a path)
// must not start a second one, so control characters are written escaped.
std::string one_line(std::string_view text) {
    std::string line;
    for (const char c : text) {
        if (c == '\n')
            line += "\\n";
        else if (c == '\r')
            line += "\\r";
        else if (static_cast<unsigned char>(c) < 0x20 && c != '\t')
            line += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
        else
            line += c;
    }
    return line;
}

void report(std::string_view command, std::string_view message) {
    fmt::print(stderr, "{}: error: {}\n", command, one_line(message));
}

}  // namespace

std::optional<int> parse_command_line(CLI::App& app, int argc, const char* const* argv,
                                      std::string_view command) {
    spiral_cli::require_plain_numbers(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        fmt::print("{}", app.help());
        return 0;
    } catch (const CLI::ParseError& error) {
        // CLI11 messages can span lines; the contract is one line.
        std::string message = error.what();
        std::replace(message.begin(), message.end(), '\n', ' ');
        report(command, message);
        return exit_bad_input;
    }
    return std::nullopt;
}

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
        report(command, error.what());
        return exit_bad_input;
    } catch (const spiral::fileio::WriteError& error) {  // output path or full disk
        report(command, error.what());
        return exit_bad_input;
    } catch (const std::filesystem::filesystem_error& error) {
        // A path given on the command line that cannot be examined or made (a
        // symlink loop, an over-long name, /proc): the input's fault. Named
        // without the library's "filesystem error: status:" prefix.
        const std::string path = error.path1().string();
        report(command, path.empty() ? error.code().message()
                                     : fmt::format("'{}': {}", path, error.code().message()));
        return exit_bad_input;
    } catch (const std::exception& error) {
        report(command, error.what());
        return 1;
    }
}

}  // namespace deepgi_app
