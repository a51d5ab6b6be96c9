// The --help layout every command-line front end shares (deepgi, its
// subcommands, spiralgen): an option's line carries its value's kind in words
// and its help ends with its default, so nothing of the parser's own notation
// (validator descriptions, "{false}" flag values, "=" defaults) reaches the
// user. An option's default is its default_str(); a flag's is "off"; a
// required option says so instead.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <string_view>

namespace spiral_apps {

class HelpFormatter : public CLI::Formatter {
public:
    // A flag takes no value (CLI11 gives it one expected value of size 1 but
    // an expected count of 0).
    static bool is_flag(const CLI::Option* option) {
        return option->get_type_size_max() == 0 || option->get_expected_max() == 0;
    }

    std::string make_option_opts(const CLI::Option* option) const override {
        if (is_flag(option)) return "";
        std::string kind = option->get_type_name();
        // Validators append ":DESCRIPTION"; the help text says the limits.
        kind = kind.substr(0, kind.find(':'));
        if (kind == "INT" || kind == "UINT") kind = "INTEGER";
        if (kind == "FLOAT") kind = "NUMBER";
        std::string out = " " + kind;
        if (option->get_expected_max() > 1) out += " ...";
        return out;
    }

    std::string make_option_desc(const CLI::Option* option) const override {
        std::string text = option->get_description();
        if (option->get_name() == "--help") return text;
        if (option->get_required()) return text + " (required)";
        if (is_flag(option)) return text + " (default: off)";
        const std::string value = option->get_default_str();
        return text + " (default: " + (value.empty() ? std::string("none") : value) + ")";
    }
};

// "0.5 metres", "1 metre": a default with its unit, for default_str().
inline std::string with_unit(double value, std::string_view unit) {
    std::string number = CLI::detail::to_string(value);
    if (unit.empty()) return number;
    const bool one = value == 1.0 && !unit.empty() && unit.back() == 's';
    return number + " " + std::string(one ? unit.substr(0, unit.size() - 1) : unit);
}

// The default of a length that `auto` derives from the scene (ao-radius,
// radiosity-radius, min-separation, ...), as deepgi and its subcommands show it.
inline constexpr const char* scene_length_default = "auto, from the scene's size";

// Installs the formatter on an app; its subcommands inherit it.
inline void use_help_formatter(CLI::App& app) {
    app.formatter(std::make_shared<HelpFormatter>());
}

}  // namespace spiral_apps
