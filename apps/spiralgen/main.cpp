// spiralgen: the command-line front end of the optimizer and the code generator.
#include <cstdio>
#include <string>

#include <fmt/core.h>

#include "commands.hpp"
#include "help_formatter.hpp"

namespace {

// Every failure is reported on one line, whatever the message looked like.
int fail(std::string message) {
    for (char& c : message)
        if (c == '\n' || c == '\r') c = ' ';
    while (!message.empty() && message.back() == ' ') message.pop_back();
    fmt::print(stderr, "spiralgen: error: {}\n", message);
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "spiralgen: optimal spiral sample patterns and the shader headers that carry them"};
    app.name("spiralgen");
    app.require_subcommand(1);
    // Before the subcommands: they inherit the formatter when added.
    spiral_apps::use_help_formatter(app);
    spiralgen::add_table_command(app);
    spiralgen::add_discrepancy_command(app);
    spiralgen::add_header_command(app);
    spiralgen::add_blur_command(app);

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        return fail(e.what());
    } catch (const std::exception& e) {
        return fail(e.what());
    }
    return 0;
}
