// spiralgen ties: every exact minimiser of D(n, tau), its band profile and the
// one the tie-break picks (docs/design.md, section 2, "Ties").
#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <fmt/ranges.h>

#include "commands.hpp"
#include "spiral/codegen.hpp"
#include "spiral/optimizer.hpp"

namespace spiralgen {
namespace {

struct TiesArgs {
    int n = 0;
    std::int64_t denominator = 1;
    std::string format = "text";
};

// The profile's sum in decimal while it fits 64 bits, else as its two halves.
std::string sum_text(const spiral::ProfileSum& sum) {
    if (sum.high < (std::int64_t{1} << 32)) return fmt::format("{}", (sum.high << 30) + sum.low);
    return fmt::format("{} * 2^30 + {}", sum.high, sum.low);
}

std::string turns_text(std::int64_t p, std::int64_t m) {
    return m == 1 ? fmt::format("{}", p) : fmt::format("{}/{}", p, m);
}

void run_ties(const TiesArgs& args) {
    if (args.n < 1 || args.n > spiral::kMaxTaps)
        throw UsageError(fmt::format("--n {} is outside [1, {}]", args.n, spiral::kMaxTaps));
    check_denominator(args.denominator, args.n);
    if (args.format != "text" && args.format != "csv")
        throw UsageError(fmt::format("unknown --format '{}' (expected text or csv)", args.format));
    const std::int64_t m = args.denominator;
    const std::int64_t nm = std::int64_t{args.n} * m;
    const spiral::SearchResult result = spiral::search(args.n, spiral::SearchOptions{0, m});

    std::string text;
    if (args.format == "csv") {
        text = "n,tau,p,m,picked,mirror,K,profile\n";
    } else {
        text = fmt::format(
            "n = {}: {} minimiser{} of D = {} / {} = {:.9g}; the tie-break picks tau = {}\n"
            "band profile: entry k is the worst 4 n^2 m * local error over the sectors whose "
            "radial extent holds k tap radii (k = 0..n); the smallest sum is picked, the "
            "smallest tau among equal sums; entries shown largest first\n",
            args.n, result.ties.size(), result.ties.size() == 1 ? "" : "s", result.scaled,
            result.denominator(), result.value(), turns_text(result.tau, m));
    }
    for (const int p : result.ties) {
        const std::vector<std::int64_t> profile = spiral::band_profile(args.n, p, m);
        const std::int64_t mirror = p == nm ? nm : nm - p;
        const bool picked = p == result.tau;
        if (args.format == "csv") {
            text += fmt::format("{},{},{},{},{},{},{},{}\n", args.n, turns_text(p, m), p, m,
                                picked ? 1 : 0, turns_text(mirror, m), result.scaled,
                                fmt::join(profile, " "));
            continue;
        }
        std::vector<std::int64_t> sorted = profile;
        std::sort(sorted.rbegin(), sorted.rend());
        constexpr std::size_t kShown = 12;
        const bool cut = sorted.size() > kShown;
        if (cut) sorted.resize(kShown);
        text += fmt::format("  tau = {:<8} {} mirror {:<8} sum {:<10} profile {}{}\n",
                            turns_text(p, m), picked ? "picked" : "      ", turns_text(mirror, m),
                            sum_text(spiral::band_profile_sum(profile)), fmt::join(sorted, " "),
                            cut ? " ..." : "");
    }
    spiral::codegen::write_stdout(text);
}

}  // namespace

void add_ties_command(CLI::App& app) {
    auto args = std::make_shared<TiesArgs>();
    CLI::App* command = app.add_subcommand(
        "ties", "Every exact minimiser of D(n, tau), its band profile, and the tie-break's pick");
    command->add_option("--n", args->n, "Tap count")->required();
    command->add_option("--denominator", args->denominator, "Search fractional turns tau = p / M")
        ->default_str("1, integer turns");
    command->add_option("--format", args->format, "Output format: text or csv")
        ->capture_default_str();
    command->callback([args] { run_ties(*args); });
}

}  // namespace spiralgen
