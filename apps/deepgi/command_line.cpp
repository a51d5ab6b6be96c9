#include "command_line.hpp"

#include "deepgi/errors.hpp"

#include <fmt/format.h>
#include <spiral/fileio.hpp>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>

namespace deepgi_app {

std::optional<int> parse_command_line(CLI::App& app, int argc, const char* const* argv,
                                      std::string_view command) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        fmt::print("{}", app.help());
        return 0;
    } catch (const CLI::ParseError& error) {
        // CLI11 messages can span lines; the contract is one line.
        std::string message = error.what();
        std::replace(message.begin(), message.end(), '\n', ' ');
        fmt::print(stderr, "{}: error: {}\n", command, message);
        return exit_bad_input;
    }
    return std::nullopt;
}

int run_reporting_errors(std::string_view command, const std::function<int()>& work) {
    try {
        return work();
    } catch (const deepgi::InputError& error) {
        fmt::print(stderr, "{}: error: {}\n", command, error.what());
        return exit_bad_input;
    } catch (const spiral::fileio::WriteError& error) {  // output path or full disk
        fmt::print(stderr, "{}: error: {}\n", command, error.what());
        return exit_bad_input;
    } catch (const std::exception& error) {
        fmt::print(stderr, "{}: error: {}\n", command, error.what());
        return 1;
    }
}

}  // namespace deepgi_app
