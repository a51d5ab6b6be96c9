// The per-pass gather header: tap count, turns, unrotated offsets and alphas.
#include "text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>

namespace spiral::codegen {

std::string macro_prefix(std::string_view pass_name) {
    constexpr std::size_t max_length = 64;
    if (pass_name.empty()) throw std::invalid_argument("pass name is empty");
    if (pass_name.size() > max_length)
        throw std::invalid_argument(
            fmt::format("pass name is longer than {} characters", max_length));
    std::string prefix;
    bool pending_separator = false;
    for (char c : pass_name) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20 || byte >= 0x7f)
            throw std::invalid_argument("pass name has characters outside printable ASCII");
        const bool letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
        const bool digit = c >= '0' && c <= '9';
        if (!letter && !digit) {
            pending_separator = !prefix.empty();
            continue;
        }
        if (pending_separator) prefix += '_';
        pending_separator = false;
        prefix += (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
    }
    const std::string shown = detail::printable_ascii(pass_name);
    if (prefix.empty())
        throw std::invalid_argument(fmt::format("pass name '{}' has no letter or digit", shown));
    if (prefix.front() >= '0' && prefix.front() <= '9')
        throw std::invalid_argument(
            fmt::format("pass name '{}' starts with a digit; a macro prefix cannot", shown));
    if (prefix.starts_with("GL_"))
        throw std::invalid_argument(fmt::format(
            "pass name '{}' gives the prefix {}, which GLSL reserves (GL_)", shown, prefix));
    return prefix;
}

std::vector<Tap> spiral_taps(int n, std::int64_t tau, std::int64_t denominator) {
    if (n < 1) throw std::invalid_argument(fmt::format("tap count must be >= 1, got {}", n));
    if (tau < 1) throw std::invalid_argument(fmt::format("tau must be >= 1, got {}", tau));
    if (denominator < 1 || denominator > kMaxScaledDenominator / (4 * std::int64_t{n} * n))
        throw std::invalid_argument(
            fmt::format("turn denominator must be in [1, 2^60 / (4 n^2)], got {}", denominator));
    const std::int64_t two_n = 2 * std::int64_t{n};
    // The angular unit is 1/(2nm) of a turn: with N = nm below, everything
    // reads as the integer case (m = 1 gives the same arithmetic, bit for bit).
    const std::int64_t big_n = std::int64_t{n} * denominator, circle = 2 * big_n;
    std::vector<Tap> taps;
    taps.reserve(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        const std::int64_t odd = 2 * std::int64_t{i} + 1;
        const double alpha = double(odd) / double(two_n);
        // Tap i is at m / (2N) turns, i.e. 2m / N quarter turns: quadrant
        // 2m div N, plus rem / N of a quarter turn. Folding rem into [0, N/2]
        // keeps the argument of cos/sin within pi/4, and a whole quarter turn
        // comes out as exact 0 and 1.
        const std::int64_t m = (odd * (tau % circle)) % circle;
        const std::int64_t quadrant = (2 * m) / big_n;
        const std::int64_t rem = 2 * m - quadrant * big_n;
        double c = 1, s = 0;
        if (2 * rem <= big_n) {
            const double angle = std::numbers::pi / 2 * double(rem) / double(big_n);
            c = std::cos(angle);
            s = std::sin(angle);
        } else {
            const double complement = std::numbers::pi / 2 * double(big_n - rem) / double(big_n);
            c = std::sin(complement);
            s = std::cos(complement);
        }
        double x = c, y = s;
        switch (quadrant) {
            case 0:
                break;
            case 1:
                x = -s;
                y = c;
                break;
            case 2:
                x = -c;
                y = -s;
                break;
            default:
                x = s;
                y = -c;
                break;
        }
        // + 0.0f turns -0 into +0, so equal patterns give equal bits.
        taps.push_back(Tap{static_cast<float>(alpha), static_cast<float>(alpha * x) + 0.0f,
                           static_cast<float>(alpha * y) + 0.0f});
    }
    return taps;
}

namespace {

// tau as written in a header: the integer, or p/m for fractional turns.
std::string turns_text(std::int64_t tau, std::int64_t m) {
    return m == 1 ? fmt::format("{}", tau) : fmt::format("{}/{}", tau, m);
}

std::string discrepancy_text(int n, const std::string& tau, std::int64_t scaled,
                             std::int64_t denominator) {
    return fmt::format("D({}, {}) = {}/{} = {}", n, tau, scaled, denominator,
                       detail::double_text(double(scaled) / double(denominator)));
}

}  // namespace

std::string format_gather_header(const GatherSpec& spec, const Provenance& provenance) {
    const std::string prefix = macro_prefix(spec.pass);
    const SearchResult& optimum = spec.optimum;
    const Discrepancy& chosen = spec.chosen;
    const int n = optimum.n;
    if (n < 1 || chosen.n != n)
        throw std::invalid_argument(fmt::format(
            "gather header: chosen pattern has n = {}, optimum has n = {}", chosen.n, n));
    if (chosen.m != optimum.m)
        throw std::invalid_argument(
            fmt::format("gather header: chosen turns have denominator {}, optimum has {}", chosen.m,
                        optimum.m));
    const std::int64_t m = optimum.m;
    if (chosen.scaled < optimum.scaled)
        throw std::invalid_argument(
            fmt::format("gather header: chosen tau {} has K = {}, below the optimum's {}",
                        chosen.tau, chosen.scaled, optimum.scaled));
    const bool ties_optimum =
        std::find(optimum.ties.begin(), optimum.ties.end(), chosen.tau) != optimum.ties.end();
    if (ties_optimum && chosen.scaled != optimum.scaled)
        throw std::invalid_argument(
            fmt::format("gather header: tau {} is listed as optimal but has K = {}, not {}",
                        chosen.tau, chosen.scaled, optimum.scaled));

    const std::int64_t den = optimum.denominator();
    const std::string pass = detail::printable_ascii(spec.pass);
    std::vector<std::string> tie_texts;
    for (const int tie : optimum.ties) tie_texts.push_back(turns_text(tie, m));
    const std::string ties = fmt::format("{}", fmt::join(tie_texts, ", "));
    const std::string chosen_tau = turns_text(chosen.tau, m),
                      optimum_tau = turns_text(optimum.tau, m);
    const std::string optimum_text = discrepancy_text(n, optimum_tau, optimum.scaled, den);
    const std::string chosen_text = discrepancy_text(n, chosen_tau, chosen.scaled, den);
    const std::string space =
        m == 1 ? fmt::format("tau in [1, {}]", n)
               : fmt::format("tau = p/{} with p in [1, {}]", m, std::int64_t{n} * m);

    std::string verdict;
    std::string inputs;
    if (chosen.tau == optimum.tau) {
        inputs = fmt::format("pass \"{}\", taps = {}, tau = {} (the optimum)", pass, n, chosen_tau);
        verdict = fmt::format("// {}: the minimum over {}, reached by tau = {}.\n", optimum_text,
                              space, ties);
    } else if (chosen.scaled == optimum.scaled) {
        inputs =
            fmt::format("pass \"{}\", taps = {}, tau = {} (set by hand; ties with the optimum)",
                        pass, n, chosen_tau);
        verdict = fmt::format(
            "// tau = {} was set by hand. It is not the tie-break's choice among the optimal\n"
            "// tau ({}, docs/design.md, section 2) but its discrepancy is the same: {}.\n",
            chosen_tau, optimum_tau, chosen_text);
    } else {
        inputs = fmt::format("pass \"{}\", taps = {}, tau = {} (set by hand; NOT the optimum)",
                             pass, n, chosen_tau);
        verdict = fmt::format(
            "// tau = {} was set by hand and is NOT the optimum. Its discrepancy is worse by\n"
            "// {}/{} = {}:\n"
            "//   chosen:  {}\n"
            "//   optimum: {} (tau = {})\n",
            chosen_tau, chosen.scaled - optimum.scaled, den,
            detail::double_text(double(chosen.scaled - optimum.scaled) / double(den)), chosen_text,
            optimum_text, ties);
    }

    const std::vector<Tap> taps = spiral_taps(n, chosen.tau, m);
    std::string out =
        detail::banner(provenance, fmt::format("Spiral taps for pass \"{}\"", pass), inputs);
    out += fmt::format(
        "//\n"
        "// Tap i (0 <= i < {0}_NUM_TAPS) lies at radius fraction alpha_i = (i + 1/2) / n and\n"
        "// angle 2*pi*tau*alpha_i + phi, phi being the per-pixel rotation. {0}_TAP_OFFSETS[i]\n"
        "// is alpha_i * (cos, sin)(2*pi*tau*alpha_i), the tap at phi = 0: rotate it by phi\n"
        "// with one 2x2 matrix and scale by the radius. {0}_TAP_ALPHAS[i] is alpha_i, for\n"
        "// choosing the MIP level without a length(). Values are float-rounded from double\n"
        "// and printed so that they read back exactly.\n"
        "//\n"
        "// Annular-sector discrepancy (docs/design.md, section 2), D = K/4n^2{1}:\n",
        prefix, m == 1 ? "" : "m");
    out += verdict;
    out += fmt::format(
        "#ifndef SPIRAL_{0}_TAPS_GLSL\n"
        "#define SPIRAL_{0}_TAPS_GLSL\n"
        "\n"
        "#define {0}_NUM_TAPS {1}\n"
        "#define {0}_NUM_SPIRAL_TURNS {2}\n"
        "{3}"
        "\n"
        "const vec2 {0}_TAP_OFFSETS[{0}_NUM_TAPS] = vec2[](\n",
        prefix, n,
        m == 1 ? fmt::format("{}", chosen.tau)
               : detail::float_literal(static_cast<float>(double(chosen.tau) / double(m))),
        m == 1 ? std::string()
               : fmt::format("#define {0}_SPIRAL_TURNS_NUMERATOR {1}\n"
                             "#define {0}_SPIRAL_TURNS_DENOMINATOR {2}\n",
                             prefix, chosen.tau, m));
    for (int i = 0; i < n; ++i) {
        const Tap& tap = taps[static_cast<std::size_t>(i)];
        out += fmt::format("    vec2({}, {}){}  // {}\n", detail::float_literal(tap.x),
                           detail::float_literal(tap.y), i + 1 < n ? "," : "", i);
    }
    out += fmt::format(");\n\nconst float {0}_TAP_ALPHAS[{0}_NUM_TAPS] = float[](\n", prefix);
    for (int i = 0; i < n; ++i)
        out += fmt::format("    {}{}  // {}\n",
                           detail::float_literal(taps[static_cast<std::size_t>(i)].alpha),
                           i + 1 < n ? "," : "", i);
    out += fmt::format(");\n\n#endif  // SPIRAL_{}_TAPS_GLSL\n", prefix);
    return out;
}

std::string make_gather_header(std::string_view pass, int taps, std::optional<int> tau,
                               const Provenance& provenance, std::int64_t denominator) {
    macro_prefix(pass);  // reject a bad name before spending time on the search
    if (taps < 1 || taps > kMaxGatherTaps)
        throw std::invalid_argument(
            fmt::format("tap count must be in [1, {}], got {}", kMaxGatherTaps, taps));
    if (tau && *tau < 1) throw std::invalid_argument(fmt::format("tau must be >= 1, got {}", *tau));
    GatherSpec spec;
    spec.pass = std::string(pass);
    spec.optimum = search(taps, SearchOptions{0, denominator});
    const int chosen_tau = tau.value_or(spec.optimum.tau);
    // D is periodic in tau with period n (numerator period nm), but the
    // pattern is not (tau + n turns every tap by half a turn), so the header
    // keeps the tau as given.
    const std::int64_t period = std::int64_t{taps} * denominator;
    spec.chosen = discrepancy(taps, (chosen_tau - 1) % period + 1, denominator);
    spec.chosen.tau = chosen_tau;
    return format_gather_header(spec, provenance);
}

}  // namespace spiral::codegen
