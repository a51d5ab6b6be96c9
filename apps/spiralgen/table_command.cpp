// spiralgen table: the optimal turns for a range of tap counts.
#include <unistd.h>

#include <cstdio>
#include <memory>
#include <string>

#include <fmt/core.h>

#include "commands.hpp"
#include "spiral/codegen.hpp"
#include "spiral/optimizer.hpp"

namespace spiralgen {
namespace {

struct TableArgs {
    int min_n = 1;
    int max_n = 99;
    std::string format = "md";
    std::string out;
    int jobs = 0;
    std::int64_t denominator = 1;
    bool compare_published = false;
};

void draw_progress(int done, int total) {
    constexpr int kWidth = 40;
    const int filled = done * kWidth / total;
    fmt::print(stderr, "\rspiralgen table: tap counts searched [{}{}] {}/{}",
               std::string(static_cast<std::size_t>(filled), '#'),
               std::string(static_cast<std::size_t>(kWidth - filled), ' '), done, total);
    if (done == total) fmt::print(stderr, "\n");
    std::fflush(stderr);
}

// The published table against the optimum (docs/optimizer.md, "The published
// table").
void run_compare_published(const TableArgs& args, const CLI::App& command) {
    for (const char* name : {"--min-n", "--max-n", "--denominator"})
        if (command.count(name) > 0)
            throw UsageError(fmt::format(
                "{} does not apply with --compare-published (it covers the published n = 1..{})",
                name, spiral::published_turns().size()));
    if (args.format != "md" && args.format != "csv")
        throw UsageError(
            fmt::format("--compare-published writes md or csv, not --format '{}'", args.format));
    if (args.jobs < 0)
        throw UsageError(
            fmt::format("--jobs {} is negative (0 means all hardware threads)", args.jobs));
    const std::string text =
        format_published_comparison(spiral::compare_published(args.jobs), args.format == "csv");
    if (args.out.empty())
        spiral::codegen::write_stdout(text);
    else
        spiral::codegen::write_file_atomically(args.out, text);
}

void run_table(const TableArgs& args) {
    if (args.min_n < 1 || args.min_n > spiral::kMaxTaps)
        throw UsageError(
            fmt::format("--min-n {} is outside [1, {}]", args.min_n, spiral::kMaxTaps));
    if (args.max_n < 1 || args.max_n > spiral::kMaxTaps)
        throw UsageError(
            fmt::format("--max-n {} is outside [1, {}]", args.max_n, spiral::kMaxTaps));
    if (args.min_n > args.max_n)
        throw UsageError(
            fmt::format("--min-n {} is larger than --max-n {}", args.min_n, args.max_n));
    if (args.jobs < 0)
        throw UsageError(
            fmt::format("--jobs {} is negative (0 means all hardware threads)", args.jobs));
    check_denominator(args.denominator, args.max_n);
    const auto format = spiral::codegen::parse_table_format(args.format);
    if (!format)
        throw UsageError(fmt::format("unknown --format '{}' (expected cpp, glsl, json, csv or md)",
                                     args.format));

    // The command is recorded without --out or --jobs: neither changes the bytes.
    // --denominator 1 is today's table and is recorded as it always was.
    std::string command = fmt::format("spiralgen table --min-n {} --max-n {} --format {}",
                                      args.min_n, args.max_n, args.format);
    if (args.denominator != 1) command += fmt::format(" --denominator {}", args.denominator);
    const spiral::codegen::Provenance provenance{command};

    const bool show_progress = isatty(fileno(stderr)) != 0;
    const auto results = spiral::search_range(args.min_n, args.max_n,
                                              spiral::SearchOptions{args.jobs, args.denominator},
                                              show_progress ? draw_progress : nullptr);
    const std::string text = spiral::codegen::format_table(results, *format, provenance);
    if (args.out.empty())
        spiral::codegen::write_stdout(text);
    else
        spiral::codegen::write_file_atomically(args.out, text);
}

}  // namespace

void add_table_command(CLI::App& app) {
    auto args = std::make_shared<TableArgs>();
    CLI::App* command =
        app.add_subcommand("table", "Tabulate the optimal spiral turns tau for each tap count n");
    command->add_option("--min-n", args->min_n, "Smallest tap count n")->default_str("n = 1");
    command->add_option("--max-n", args->max_n, "Largest tap count n")->default_str("n = 99");
    command->add_option("--format", args->format, "Output format: cpp, glsl, json, csv or md")
        ->capture_default_str();
    command
        ->add_option("--out", args->out,
                     "Write to this file (atomically) instead of standard output ('-')")
        ->check(non_empty_path)
        ->default_str("standard output");
    command->add_option("--jobs", args->jobs, "Worker threads (0: all hardware threads)")
        ->default_str("0, all hardware threads");
    command->add_option("--denominator", args->denominator, "Search fractional turns tau = p / M")
        ->default_str("1, integer turns");
    command->add_flag("--compare-published", args->compare_published,
                      "Compare the deep G-buffer paper's published tau table (n = 1..98) with the "
                      "exact optimum: per n the published tau, its exact D and a verdict (ties, "
                      "indexed one off, worse); md or csv");
    command->callback([args, command] {
        if (args->compare_published)
            run_compare_published(*args, *command);
        else
            run_table(*args);
    });
}

}  // namespace spiralgen

namespace spiralgen {

void check_denominator(std::int64_t denominator, int max_n) {
    if (denominator < 1)
        throw UsageError(fmt::format("--denominator {} must be a positive integer", denominator));
    const std::int64_t four_n_squared = 4 * std::int64_t{max_n} * max_n;
    if (denominator > spiral::kMaxScaledDenominator / four_n_squared)
        throw UsageError(fmt::format(
            "--denominator {} with n = {} overflows 64-bit exact arithmetic: 4 n^2 m must be at "
            "most 2^60, so m <= {}",
            denominator, max_n, spiral::kMaxScaledDenominator / four_n_squared));
    if (std::int64_t{max_n} * denominator > spiral::kMaxSearchCandidates)
        throw UsageError(fmt::format(
            "--denominator {} with n = {} gives n m = {} candidates, above the limit 2^30",
            denominator, max_n, std::int64_t{max_n} * denominator));
}

}  // namespace spiralgen
