// spiralgen: the command-line front end of the optimizer and the code generator.
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <spiral/fileio.hpp>

#include "../strict_numbers.hpp"
#include "command_line_errors.hpp"
#include "commands.hpp"
#include "help_formatter.hpp"

namespace {

// Every failure is reported on one line, whatever the message looked like.
int fail(std::string message) {
    for (char& c : message)
        if (c == '\n' || c == '\r') c = ' ';
    while (!message.empty() && message.back() == ' ') message.pop_back();
    std::string line;
    for (const char c : message) {
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t')
            line += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
        else
            line += c;
    }
    fmt::print(stderr, "spiralgen: error: {}\n", line);
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
    spiralgen::add_ties_command(app);
    spiralgen::add_header_command(app);
    spiralgen::add_blur_command(app);
    spiral_cli::require_plain_numbers(app);

    try {
        app.parse(argc, argv);
        // Standard output is an output like any other (a full disk, a closed
        // pipe with SIGPIPE ignored): checked before exit 0.
        spiral::fileio::close_standard_output();
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // No known subcommand: name them all, and the word given instead if
        // any, rather than CLI11's bare "A subcommand is required".
        if (dynamic_cast<const CLI::RequiredError*>(&e) != nullptr &&
            app.get_subcommands().empty()) {
            std::vector<std::string> names;
            for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; }))
                names.push_back(command->get_name());
            const std::vector<std::string> words = app.remaining();
            if (!words.empty())
                return fail(
                    fmt::format("'{}' is not a subcommand; the subcommands are {} "
                                "(spiralgen --help describes them)",
                                words.front(), fmt::join(names, ", ")));
            return fail(
                fmt::format("a subcommand is required: {} (spiralgen --help describes them)",
                            fmt::join(names, ", ")));
        }
        return fail(spiral_apps::describe_parse_error(e));
    } catch (const std::exception& e) {
        return fail(e.what());
    }
    return 0;
}
