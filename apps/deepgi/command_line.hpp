#pragma once
// What every deepgi command (the renderer, `reference`, `report`) does with a
// command line it cannot parse and with the errors its work throws: one line
// on stderr that starts with the command's name, exit status 2 for bad input
// and 1 for anything else. The parse errors are command_line_errors.hpp's,
// shared with the measuring tools.
#include "command_line_errors.hpp"

#include <CLI/CLI.hpp>

#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace deepgi_app {

using spiral_apps::exit_bad_input;
// Returns the exit status when the command should stop here: 0 after
// printing --help, exit_bad_input after a parse error.
using spiral_apps::parse_command_line;

// The end of `deepgi --help`: the subcommands, every scene --scene accepts,
// and the window's keys, so that nothing the program does needs the docs to
// be found.
std::string help_footer();

// Runs the command's work; InputError and output-file errors are bad input.
int run_reporting_errors(std::string_view command, const std::function<int()>& work);

}  // namespace deepgi_app
