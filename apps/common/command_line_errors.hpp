// What a command-line program of the project does with a command line it
// cannot parse: one line on stderr that starts with the program's name and
// names the problem, and exit status 2. Shared by deepgi (and its
// subcommands) and the measuring tools beside the reference.
#pragma once

#include "../strict_numbers.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

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

// CLI11's message, except for its two most common in a user's words: an
// option given twice ("--size: At Most 1 required but received 2") and a
// word no option takes ("The following argument was not expected: ...",
// whose words CLI11 lists last first).
inline std::string describe_parse_error(const CLI::ParseError& error) {
    const std::string message = error.what();
    if (dynamic_cast<const CLI::ArgumentMismatch*>(&error) != nullptr) {
        const std::string marker = ": At Most 1 required but received ";
        if (const auto at = message.find(marker); at != std::string::npos)
            return fmt::format("{} was given {} times; give it once", message.substr(0, at),
                               message.substr(at + marker.size()));
    }
    // Plain numbers only reach CLI11's conversion (strict_numbers.hpp), so a
    // failed conversion is a number the option's type cannot hold:
    // "Could not convert: --frames = 99999999999".
    if (dynamic_cast<const CLI::ConversionError*>(&error) != nullptr) {
        const std::string marker = "Could not convert: ";
        const auto at = message.find(marker);
        const auto equals = message.find(" = ", at == std::string::npos ? 0 : at);
        if (at != std::string::npos && equals != std::string::npos)
            return fmt::format("{} '{}' is out of range for this option",
                               message.substr(at + marker.size(), equals - at - marker.size()),
                               message.substr(equals + 3));
    }
    if (dynamic_cast<const CLI::ExtrasError*>(&error) != nullptr) {
        const auto colon = message.find(": ");
        std::vector<std::string> words;
        std::istringstream list(colon == std::string::npos ? "" : message.substr(colon + 2));
        for (std::string word; list >> word;) words.insert(words.begin(), word);
        const auto option = std::find_if(words.begin(), words.end(), [](const std::string& w) {
            return w.size() > 1 && w[0] == '-' && !std::isdigit(static_cast<unsigned char>(w[1])) &&
                   w[1] != '.';
        });
        if (option != words.end())
            return fmt::format("unknown option '{}' (--help lists the options)", *option);
        if (!words.empty())
            return fmt::format("unexpected argument '{}' (--help lists the options)",
                               words.front());
    }
    return message;
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
        std::string message = describe_parse_error(error);
        std::replace(message.begin(), message.end(), '\n', ' ');
        report_error(command, message);
        return exit_bad_input;
    }
    return std::nullopt;
}

}  // namespace spiral_apps
