// spiralgen discrepancy: the exact D(n, tau) and the sector that attains it,
// so a user can see why a number of turns is bad.
#include <memory>
#include <string>
#include <utility>

#include <fmt/core.h>

#include "commands.hpp"
#include "spiral/optimizer.hpp"

namespace spiralgen {
namespace {

struct DiscrepancyArgs {
    int n = 0;
    int tau = 0;
    std::string format = "text";
};

// A coordinate in half units, as a reduced fraction of a turn or of the radius.
std::string fraction(std::int64_t num, std::int64_t den) {
    if (num == 0) return "0";
    std::int64_t a = num, b = den;
    while (b != 0) a = std::exchange(b, a % b);
    if (den / a == 1) return fmt::format("{}", num / a);
    return fmt::format("{}/{}", num / a, den / a);
}

std::string describe_text(const spiral::Discrepancy& d) {
    const spiral::Sector& s = d.worst;
    const std::int64_t two_n = 2 * std::int64_t{d.n};
    const std::int64_t four_n = 2 * two_n;
    const bool too_many = s.closed;
    const std::string lo = fraction(s.radial_lo, two_n), hi = fraction(s.radial_hi, two_n);
    const std::string radius = s.closed
                                   ? fmt::format("radius from {} to {} of R (inclusive)", lo, hi)
                                   : fmt::format("radius strictly between {} and {} of R", lo, hi);
    const std::string from = fraction(s.arc_start, two_n);
    const std::string to = fraction((s.arc_start + s.arc_length) % two_n, two_n);
    std::string arc;
    if (s.arc_length == two_n)
        arc = s.closed ? "the whole circle" : fmt::format("every angle except {} turn", from);
    else
        arc = fmt::format("angle {} {} {} {} turn, counter-clockwise ({} turn)",
                          s.closed ? "from" : "strictly between", from, s.closed ? "to" : "and", to,
                          fraction(s.arc_length, two_n));
    std::string text = fmt::format("D({}, {}) = {} / {} = {:.9g}\n", d.n, d.tau, d.scaled,
                                   d.denominator(), d.value());
    text += fmt::format("worst sector ({}): {}; {}\n", s.closed ? "closed" : "open", radius, arc);
    text += fmt::format(
        "it holds {} of {} taps ({:.6g}) but its weighted area is {} ({:.6g}): {} taps\n", s.count,
        d.n, double(s.count) / d.n, fraction(s.scaled_area(), d.denominator()),
        double(s.scaled_area()) / double(d.denominator()), too_many ? "too many" : "too few");
    text += fmt::format("|4n * count - width * arc| = |{} - {}| = {} (in units of 1/(2n))\n",
                        four_n * s.count, s.scaled_area(), d.scaled);
    return text;
}

std::string describe_json(const spiral::Discrepancy& d) {
    const spiral::Sector& s = d.worst;
    const std::int64_t two_n = 2 * std::int64_t{d.n};
    return fmt::format(
        "{{\"n\":{},\"tau\":{},\"discrepancy\":{{\"num\":{},\"den\":{},\"value\":{}}},"
        "\"worst_sector\":{{\"closed\":{},\"radial\":{{\"lo\":{},\"hi\":{},\"den\":{}}},"
        "\"arc\":{{\"start\":{},\"length\":{},\"den\":{}}},\"count\":{},"
        "\"weighted_area\":{{\"num\":{},\"den\":{}}}}}}}\n",
        d.n, d.tau, d.scaled, d.denominator(), d.value(), s.closed ? "true" : "false", s.radial_lo,
        s.radial_hi, two_n, s.arc_start, s.arc_length, two_n, s.count, s.scaled_area(),
        d.denominator());
}

void run_discrepancy(const DiscrepancyArgs& args) {
    if (args.n < 1 || args.n > spiral::kMaxTaps)
        throw UsageError(fmt::format("--n {} is outside [1, {}]", args.n, spiral::kMaxTaps));
    if (args.tau < 1) throw UsageError(fmt::format("--tau {} must be at least 1", args.tau));
    if (args.format != "text" && args.format != "json")
        throw UsageError(fmt::format("unknown --format '{}' (expected text or json)", args.format));
    const spiral::Discrepancy d = spiral::discrepancy(args.n, args.tau);
    fmt::print("{}", args.format == "json" ? describe_json(d) : describe_text(d));
}

}  // namespace

void add_discrepancy_command(CLI::App& app) {
    auto args = std::make_shared<DiscrepancyArgs>();
    CLI::App* command = app.add_subcommand(
        "discrepancy", "Exact annular-sector discrepancy of one spiral, and its worst sector");
    command->add_option("--n", args->n, "Tap count")->required();
    command->add_option("--tau", args->tau, "Number of spiral turns")->required();
    command->add_option("--format", args->format, "Output format: text or json")
        ->capture_default_str();
    command->callback([args] { run_discrepancy(*args); });
}

}  // namespace spiralgen
