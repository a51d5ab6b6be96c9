// spiralgen discrepancy: the exact D(n, tau) and the sector that attains it,
// so a user can see why a number of turns is bad.
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include <fmt/core.h>

#include "commands.hpp"
#include "spiral/optimizer.hpp"

namespace spiralgen {
namespace {

struct DiscrepancyArgs {
    int n = 0;
    std::optional<int> tau;
    std::optional<std::string> turns;
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
    const std::int64_t circle = two_n * d.m;  // angles are in units of 1/(2nm)
    const std::int64_t four_n = 2 * circle;
    const bool too_many = s.closed;
    const std::string lo = fraction(s.radial_lo, two_n), hi = fraction(s.radial_hi, two_n);
    const std::string radius = s.closed
                                   ? fmt::format("radius from {} to {} of R (inclusive)", lo, hi)
                                   : fmt::format("radius strictly between {} and {} of R", lo, hi);
    const std::string from = fraction(s.arc_start, circle);
    const std::string to = fraction((s.arc_start + s.arc_length) % circle, circle);
    std::string arc;
    if (s.arc_length == circle)
        arc = s.closed ? "the whole circle" : fmt::format("every angle except {} turn", from);
    else
        arc = fmt::format("angle {} {} {} {} turn, counter-clockwise ({} turn)",
                          s.closed ? "from" : "strictly between", from, s.closed ? "to" : "and", to,
                          fraction(s.arc_length, circle));
    const std::string tau = d.m == 1 ? fmt::format("{}", d.tau) : fmt::format("{}/{}", d.tau, d.m);
    std::string text = fmt::format("D({}, {}) = {} / {} = {:.9g}\n", d.n, tau, d.scaled,
                                   d.denominator(), d.value());
    text += fmt::format("worst sector ({}): {}; {}\n", s.closed ? "closed" : "open", radius, arc);
    text += fmt::format(
        "it holds {} of {} taps ({:.6g}) but its weighted area is {} ({:.6g}): {} taps\n", s.count,
        d.n, double(s.count) / d.n, fraction(s.scaled_area(), d.denominator()),
        double(s.scaled_area()) / double(d.denominator()), too_many ? "too many" : "too few");
    if (d.m == 1)
        text += fmt::format("|4n * count - width * arc| = |{} - {}| = {} (in units of 1/(2n))\n",
                            four_n * s.count, s.scaled_area(), d.scaled);
    else
        text += fmt::format(
            "|4nm * count - width * arc| = |{} - {}| = {} (radius in 1/(2n), angle in "
            "1/(2nm))\n",
            four_n * s.count, s.scaled_area(), d.scaled);
    return text;
}

std::string describe_json(const spiral::Discrepancy& d) {
    const spiral::Sector& s = d.worst;
    const std::int64_t two_n = 2 * std::int64_t{d.n};
    const std::int64_t circle = two_n * d.m;
    if (d.m != 1)
        return fmt::format(
            "{{\"n\":{},\"p\":{},\"m\":{},\"discrepancy\":{{\"num\":{},\"den\":{},\"value\":{}}},"
            "\"worst_sector\":{{\"closed\":{},\"radial\":{{\"lo\":{},\"hi\":{},\"den\":{}}},"
            "\"arc\":{{\"start\":{},\"length\":{},\"den\":{}}},\"count\":{},"
            "\"weighted_area\":{{\"num\":{},\"den\":{}}}}}}}\n",
            d.n, d.tau, d.m, d.scaled, d.denominator(), d.value(), s.closed ? "true" : "false",
            s.radial_lo, s.radial_hi, two_n, s.arc_start, s.arc_length, circle, s.count,
            s.scaled_area(), d.denominator());
    return fmt::format(
        "{{\"n\":{},\"tau\":{},\"discrepancy\":{{\"num\":{},\"den\":{},\"value\":{}}},"
        "\"worst_sector\":{{\"closed\":{},\"radial\":{{\"lo\":{},\"hi\":{},\"den\":{}}},"
        "\"arc\":{{\"start\":{},\"length\":{},\"den\":{}}},\"count\":{},"
        "\"weighted_area\":{{\"num\":{},\"den\":{}}}}}}}\n",
        d.n, d.tau, d.scaled, d.denominator(), d.value(), s.closed ? "true" : "false", s.radial_lo,
        s.radial_hi, two_n, s.arc_start, s.arc_length, two_n, s.count, s.scaled_area(),
        d.denominator());
}

// A rational approximation of real turns and how far D can be from it.
//
// Claim: if every tap's angle moves by at most delta (in turns), D moves by at
// most 2 delta. Proof: a tap inside a sector S lies, after the move, inside S
// widened by delta at both ends of its arc (closed stays closed), whose
// weighted area exceeds S's by at most 2 delta * width <= 2 delta; so "too
// many taps" grows by at most 2 delta. Symmetrically, a tap inside S narrowed
// by delta lies inside S after the move, which bounds "too few taps". Both
// directions give |D(tau) - D(p/m)| <= 2 delta. Tap i moves by
// |tau - p/m| * alpha_i with alpha_i < 1, so delta <= |tau - p/m|. (D is thus
// continuous in tau; it only has corners where taps swap angular order.)
struct Approximation {
    std::int64_t p = 0, m = 1;
    long double error = 0;  // an upper bound on |tau - p/m|
};

// The last continued-fraction convergent of x whose denominator keeps
// 4 n^2 m within the exact-arithmetic limit. x_error bounds |x - true tau|.
Approximation approximate(long double x, long double x_error, int n) {
    const std::int64_t max_m = spiral::kMaxScaledDenominator / (4 * std::int64_t{n} * n);
    std::int64_t p_prev = 1, m_prev = 0, p = static_cast<std::int64_t>(std::floor(x)), m = 1;
    long double rest = x - std::floor(x);
    Approximation best{p, m, std::fabs(x - static_cast<long double>(p)) + x_error};
    for (int step = 0; step < 64 && rest > 1e-18L; ++step) {
        const long double inverse = 1 / rest;
        const auto a = static_cast<std::int64_t>(std::floor(inverse));
        rest = inverse - std::floor(inverse);
        if (a > (max_m - m_prev) / std::max<std::int64_t>(m, 1)) break;
        const std::int64_t p_next = a * p + p_prev, m_next = a * m + m_prev;
        p_prev = p;
        m_prev = m;
        p = p_next;
        m = m_next;
        const long double error =
            std::fabs(x - static_cast<long double>(p) / static_cast<long double>(m));
        // The long-double quotient itself may be off by a few ulps of x.
        best = {p, m, error + x_error + 4 * x * 1.1e-19L};
    }
    return best;
}

void run_discrepancy(const DiscrepancyArgs& args) {
    if (args.n < 1 || args.n > spiral::kMaxTaps)
        throw UsageError(fmt::format("--n {} is outside [1, {}]", args.n, spiral::kMaxTaps));
    if (args.format != "text" && args.format != "json")
        throw UsageError(fmt::format("unknown --format '{}' (expected text or json)", args.format));
    if (args.tau.has_value() == args.turns.has_value())
        throw UsageError("give exactly one of --tau (an integer) and --turns (a real number)");
    if (args.tau) {
        if (*args.tau < 1) throw UsageError(fmt::format("--tau {} must be at least 1", *args.tau));
        const spiral::Discrepancy d = spiral::discrepancy(args.n, *args.tau);
        fmt::print("{}", args.format == "json" ? describe_json(d) : describe_text(d));
        return;
    }

    // The golden-angle spiral advances 1 - 1/phi = 2 - phi of a turn per tap,
    // i.e. tau / n turns per tap with tau = n (2 - phi).
    long double x = 0, x_error = 0;
    const std::string& text = *args.turns;
    if (text == "golden") {
        const long double phi = (1 + std::sqrt(5.0L)) / 2;
        x = static_cast<long double>(args.n) * (2 - phi);
        // sqrt(5) and the products carry a few ulps (2^-64 relative) each;
        // n * 1e-17 is far above that.
        x_error = static_cast<long double>(args.n) * 1e-17L;
    } else {
        std::size_t used = 0;
        try {
            x = std::stold(text, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != text.size() || text.empty() || !std::isfinite(x))
            throw UsageError(
                fmt::format("--turns '{}' is not a finite number (or 'golden')", text));
        x_error = std::fabs(x) * 1.1e-19L;  // decimal to long double rounding
    }
    if (!(x > 0) || x > static_cast<long double>(args.n))
        throw UsageError(fmt::format("--turns {} is outside (0, n] = (0, {}]", text, args.n));

    const Approximation a = approximate(x, x_error, args.n);
    if (a.p < 1)
        throw UsageError(
            fmt::format("--turns {} is too close to 0 to approximate with "
                        "4 n^2 m <= 2^60",
                        text));
    const spiral::Discrepancy d = spiral::discrepancy(args.n, a.p, a.m);
    const long double bound = 2 * a.error;
    if (args.format == "json") {
        fmt::print(
            "{{\"n\":{},\"turns\":\"{}\",\"approximation\":{{\"p\":{},\"m\":{}}},"
            "\"error_bound\":{:.3g},\"exact\":{}}}\n",
            args.n, text, a.p, a.m, static_cast<double>(bound),
            describe_json(d).substr(0, describe_json(d).size() - 1));
        return;
    }
    fmt::print("turns {} ~ {:.15Lg}, approximated by tau = {}/{} (|tau - p/m| <= {:.3Lg})\n", text,
               x, a.p, a.m, a.error);
    fmt::print("D(n = {}, tau = {}) = {:.9g} +- {:.3Lg}\n", args.n, text, d.value(), bound);
    fmt::print(
        "(moving every tap by at most delta of a turn changes D by at most 2 delta; delta <= "
        "|tau - p/m|)\n");
    fmt::print("{}", describe_text(d));
}

}  // namespace

void add_discrepancy_command(CLI::App& app) {
    auto args = std::make_shared<DiscrepancyArgs>();
    CLI::App* command = app.add_subcommand(
        "discrepancy", "Exact annular-sector discrepancy of one spiral, and its worst sector");
    command->add_option("--n", args->n, "Tap count")->required();
    command
        ->add_option("--tau", args->tau,
                     "Number of spiral turns (an integer); give --tau or --turns")
        ->default_str("none");
    command
        ->add_option("--turns", args->turns,
                     "Real number of turns in (0, n], or 'golden' for the golden-angle "
                     "spiral (tau = n (2 - phi)); evaluated through a rational "
                     "approximation with a stated error bound")
        ->default_str("none");
    command->add_option("--format", args->format, "Output format: text or json")
        ->capture_default_str();
    command->callback([args] { run_discrepancy(*args); });
}

}  // namespace spiralgen
