// The spiralgen subcommands. Each registers itself on the app; its callback
// throws UsageError (or std::exception) for bad input, which main() turns into
// a one-line message and exit status 2.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "spiral/published.hpp"

namespace spiralgen {

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// For --out: an empty path is an error (it used to mean standard output
// silently); '-' is standard output.
inline const CLI::Validator non_empty_path(
    [](std::string& path) { return path.empty() ? std::string("must not be empty") : ""; },
    "PATH|-");

// Rejects a turn denominator below 1, or one for which 4 n^2 m (n = max_n)
// or n m would overflow the optimizer's exact arithmetic, naming the limit.
void check_denominator(std::int64_t denominator, int max_n);

// The --compare-published report: a Markdown page (source, summary, one row
// per n) or, with csv, one row per n and no prose.
std::string format_published_comparison(const std::vector<spiral::PublishedComparison>& rows,
                                        bool csv);

void add_table_command(CLI::App& app);
void add_discrepancy_command(CLI::App& app);
void add_header_command(CLI::App& app);
void add_blur_command(CLI::App& app);
void add_ties_command(CLI::App& app);

}  // namespace spiralgen
