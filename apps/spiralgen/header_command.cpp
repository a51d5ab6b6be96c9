// spiralgen header: the GLSL header of one gathering pass (docs/design.md, section 4).
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <fmt/core.h>

#include "commands.hpp"
#include "spiral/codegen.hpp"
#include "spiral/optimizer.hpp"

namespace spiralgen {
namespace {

struct HeaderArgs {
    std::string pass;
    int taps = 0;
    std::optional<int> tau;
    std::string out;
    std::int64_t denominator = 1;
};

void run_header(const HeaderArgs& args) {
    namespace codegen = spiral::codegen;
    try {
        codegen::macro_prefix(args.pass);
    } catch (const std::invalid_argument& e) {
        throw UsageError(fmt::format("--pass: {}", e.what()));
    }
    if (args.taps < 1) throw UsageError(fmt::format("--taps {} is below 1", args.taps));
    if (args.tau && *args.tau < 1) throw UsageError(fmt::format("--tau {} is below 1", *args.tau));
    if (args.taps > codegen::kMaxGatherTaps)
        throw UsageError(fmt::format(
            "--taps {} is above header's limit of {} taps (the exact search that every header "
            "records grows faster than n^2)",
            args.taps, codegen::kMaxGatherTaps));
    check_denominator(args.denominator, args.taps);

    // Recorded canonically and without --out: the bytes depend only on the
    // pass, the tap count and tau, not on where they are written.
    std::string command = fmt::format("spiralgen header --pass {} --taps {}",
                                      codegen::shell_quote(args.pass), args.taps);
    if (args.tau) command += fmt::format(" --tau {}", *args.tau);
    if (args.denominator != 1) command += fmt::format(" --denominator {}", args.denominator);

    const std::string text = codegen::make_gather_header(
        args.pass, args.taps, args.tau, codegen::Provenance{command}, args.denominator);
    if (args.out.empty())
        codegen::write_stdout(text);
    else
        codegen::write_file_atomically(args.out, text);
}

}  // namespace

void add_header_command(CLI::App& app) {
    auto args = std::make_shared<HeaderArgs>();
    CLI::App* command = app.add_subcommand(
        "header", "Write the GLSL header of a gathering pass: tap count, turns, offsets, alphas");
    command->add_option("--pass", args->pass, "Pass name (free text; becomes the macro prefix)")
        ->required();
    command
        ->add_option("--taps", args->taps,
                     fmt::format("Number of taps, 1 to {}", spiral::codegen::kMaxGatherTaps))
        ->required();
    command
        ->add_option("--tau", args->tau,
                     "Number of spiral turns, overriding the optimum (the header then says "
                     "how much worse it is)")
        ->default_str("the optimum");
    command
        ->add_option("--out", args->out,
                     "Write to this file (atomically) instead of standard output ('-')")
        ->check(non_empty_path)
        ->default_str("standard output");
    command
        ->add_option("--denominator", args->denominator,
                     "Fractional turns tau = p / M: search p (and read --tau as p)")
        ->default_str("1, integer turns");
    command->callback([args] { run_header(*args); });
}

}  // namespace spiralgen
