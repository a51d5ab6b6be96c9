// What a command-line program of the project does with a command line it
// cannot parse: one line on stderr that starts with the program's name and
// names the problem, and exit status 2. Shared by deepgi (and its
// subcommands) and the measuring tools beside the reference.
#pragma once

#include "../strict_numbers.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <string>
#include <string_view>

namespace spiral_apps {

inline constexpr int exit_bad_input = 2;

// The contract is one line: a name with a newline in it (a scene, a path)
// must not start a second one, so control characters are written escaped.
inline std::string one_line(std::string_view text) {
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

// "<command>: error: <message>" on stderr, as one line.
inline void report_error(std::string_view command, std::string_view message) {
    fmt::print(stderr, "{}: error: {}\n", command, one_line(message));
}

// Parses the command line, every number on it plain decimal text
// (strict_numbers.hpp). Returns the exit status when the program should stop
// here: 0 after printing --help, exit_bad_input after a parse error.
inline std::optional<int> parse_command_line(CLI::App& app, int argc, const char* const* argv,
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
        report_error(command, message);
        return exit_bad_input;
    }
    return std::nullopt;
}

}  // namespace spiral_apps
