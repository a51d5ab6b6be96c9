// The command lines of the measuring tools beside the reference: CLI11 with
// the --help layout of deepgi and spiralgen, and deepgi's way with a command
// line it cannot parse (one line on stderr naming the problem, exit status 2:
// command_line_errors.hpp). The arguments several tools share are declared
// here once, and so is every tool's main (run_tool).
#pragma once

#include "command_line_errors.hpp"
#include "help_formatter.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/settings.hpp"

#include <CLI/CLI.hpp>

#include <charconv>
#include <exception>
#include <system_error>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace deepgi_tools {

// A tool's main: runs body(argc, argv) and returns its exit status. What
// the body throws (an image it cannot read, a dump that does not fit the
// reference) ends the tool with one line on stderr that starts with its
// name, and exit status 2.
template <typename Body>
int run_tool(const char* name, int argc, char** argv, Body body) {
    try {
        return body(argc, argv);
    } catch (const std::exception& error) {
        fmt::print(stderr, "{}: {}\n", name, error.what());
        return spiral_apps::exit_bad_input;
    }
}

// Installs the shared --help layout; the app's name starts its error lines.
inline void use_tool_layout(CLI::App& app) {
    spiral_apps::use_help_formatter(app);
}

// Parses the command line (spiral_apps::parse_command_line under the app's
// name). Returns the exit status when the tool should stop here.
inline std::optional<int> parse(CLI::App& app, int argc, const char* const* argv) {
    return spiral_apps::parse_command_line(app, argc, argv, app.get_name());
}

inline CLI::Option* add_dump_dir(CLI::App& app, std::filesystem::path& dump) {
    return app.add_option("DUMP_DIR", dump, "The folder deepgi --headless --dump wrote")
        ->required()
        ->check(CLI::ExistingDirectory);
}

inline CLI::Option* add_reference_dir(CLI::App& app, std::filesystem::path& reference) {
    return app
        .add_option("REFERENCE_DIR", reference,
                    "The folder deepgi reference wrote for the same scene, size and guard band")
        ->required()
        ->check(CLI::ExistingDirectory);
}

inline CLI::Option* add_guard_pixels(CLI::App& app, int& guard) {
    return app
        .add_option("GUARD_PIXELS", guard,
                    "The guard band's width in pixels on each side (left out of every measure)")
        ->required()
        ->check(CLI::NonNegativeNumber);
}

// The three positional arguments of every comparison tool: the dump, the
// reference of the same scene and size, and the guard band both carry.
struct DumpAndReference {
    std::filesystem::path dump;
    std::filesystem::path reference;
    int guard = 0;
};

inline void add_dump_and_reference(CLI::App& app, DumpAndReference& folders) {
    add_dump_dir(app, folders.dump);
    add_reference_dir(app, folders.reference);
    add_guard_pixels(app, folders.guard);
}

inline CLI::Option* add_scene(CLI::App& app, std::string& scene) {
    return app.add_option("SCENE", scene, "The scene of both folders, as deepgi --scene names it")
        ->required();
}

// The renderer's guard band as a fraction of the height, within the limits
// of its settings row (settings.hpp), as deepgi --guard-band.
inline CLI::Option* add_guard_band(CLI::App& app, float& fraction) {
    const deepgi::NumericSetting& row = *deepgi::find_numeric_setting("guard-band");
    return app
        .add_option("--guard-band", fraction,
                    "The guard band of the dump, a fraction of the height, as deepgi --guard-band")
        ->check(CLI::Validator(
            [&row](const std::string& text) -> std::string {
                double value = 0.0;
                const auto [end, error] =
                    std::from_chars(text.data(), text.data() + text.size(), value);
                // Not a number: the plain-number check names that.
                if (error != std::errc() || end != text.data() + text.size()) return "";
                try {
                    deepgi::check_setting(row, value);
                } catch (const deepgi::InputError& problem) {
                    return problem.what();
                }
                return "";
            },
            "", ""))
        ->capture_default_str();
}

// "X,Y,Z": exactly `count` decimal numbers separated by commas, or nullopt.
template <typename Number = float>
std::optional<std::vector<Number>> comma_numbers(std::string_view text, std::size_t count) {
    std::vector<Number> values;
    std::size_t start = 0;
    for (;;) {
        const std::size_t comma = text.find(',', start);
        const std::string_view part =
            text.substr(start, comma == std::string_view::npos ? comma : comma - start);
        Number value = 0;
        const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), value);
        if (part.empty() || error != std::errc() || end != part.data() + part.size())
            return std::nullopt;
        values.push_back(value);
        if (comma == std::string_view::npos) break;
        start = comma + 1;
    }
    if (values.size() != count) return std::nullopt;
    return values;
}

}  // namespace deepgi_tools
