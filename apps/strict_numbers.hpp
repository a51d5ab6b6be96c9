#pragma once
// Numbers on both programs' command lines are plain decimal text, whole: CLI11
// alone reads an empty value as 0, "0x10" as 16, "-1" for an unsigned
// option as its wrapped value and "4,,8" as a list with a 0 in it. Every
// integer or floating-point option of an app and its subcommands gets this
// check, so no option can forget it.
#include <CLI/CLI.hpp>

#include <charconv>
#include <cstdint>
#include <string>
#include <system_error>

namespace spiral_cli {

// "" when `text` is a plain number of the kind CLI11 names `type` (INT,
// UINT, FLOAT), else why not; the value given is quoted as given.
inline std::string plain_number_problem(const std::string& text, const std::string& type) {
    const char* begin = text.data();
    const char* end = text.data() + text.size();
    if (text.empty()) return "an empty value is not a number";
    std::errc error{};
    const char* stop = begin;
    if (type == "FLOAT") {
        double value = 0;
        const auto result = std::from_chars(begin, end, value, std::chars_format::general);
        error = result.ec;
        stop = result.ptr;
        if (error == std::errc() && stop == end) return "";
        if (error == std::errc::result_out_of_range)
            return "'" + text + "' is out of range for a double";
        return "'" + text + "' is not a decimal number";
    }
    const bool digits_only =
        text.find_first_not_of("0123456789", text[0] == '-' ? 1 : 0) == std::string::npos &&
        text != "-";
    if (!digits_only) return "'" + text + "' is not a whole decimal number";
    if (type == "UINT") {
        if (text[0] == '-') return "'" + text + "' is negative; this option takes a count >= 0";
        std::uint64_t value = 0;
        const auto result = std::from_chars(begin, end, value);
        error = result.ec;
    } else {
        std::int64_t value = 0;
        const auto result = std::from_chars(begin, end, value);
        error = result.ec;
    }
    if (error == std::errc::result_out_of_range)
        return "'" + text + "' is out of range for a 64-bit integer";
    return "";
}

inline void require_plain_numbers(CLI::App& app) {
    for (CLI::Option* option : app.get_options()) {
        // An option with a check (CLI::Range, CLI::PositiveNumber) has the
        // check's description after a colon: "INT:POSITIVE".
        std::string type = option->get_type_name();
        type = type.substr(0, type.find(':'));
        if (type != "INT" && type != "UINT" && type != "FLOAT") continue;
        // A transform, not a check: CLI11 hands a check a copy of the text.
        option->transform(CLI::Validator(
            [type](std::string& text) {
                std::string problem = plain_number_problem(text, type);
                // CLI11 reads an integer with a leading 0 as octal ("010" as
                // 8): a plain decimal integer loses its leading zeros first.
                if (problem.empty() && type != "FLOAT") {
                    const std::size_t sign = text[0] == '-' ? 1 : 0;
                    const std::size_t first = text.find_first_not_of('0', sign);
                    text.erase(sign, (first == std::string::npos ? text.size() - 1 : first) - sign);
                    if (text == "-0") text = "0";
                }
                return problem;
            },
            "", ""));
    }
    for (CLI::App* subcommand : app.get_subcommands({})) require_plain_numbers(*subcommand);
}

}  // namespace spiral_cli
