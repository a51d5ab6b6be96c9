// Tap patterns of the report and the header text the shaders include.
#include "deepgi/report.hpp"

#include <spiral/optimizer.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace deepgi::report {

namespace {

// The golden angle's denominator: with 4 n^2 m <= 2^60 this allows n up to
// 2^19, far past any tap count a gather uses.
constexpr std::int64_t kGoldenDenominator = std::int64_t{1} << 20;

std::int64_t fractional_denominator(std::string_view name) {
    if (name == "m2") return 2;
    if (name == "m4") return 4;
    if (name == "m8") return 8;
    return 0;
}

}  // namespace

const std::vector<std::string>& pattern_names() {
    static const std::vector<std::string> names = {"optimal", "tau1", "golden", "m2", "m4", "m8"};
    return names;
}

bool is_pattern_name(std::string_view name) {
    const auto& names = pattern_names();
    return std::find(names.begin(), names.end(), name) != names.end();
}

Turns pattern_turns(std::string_view name, int n) {
    if (n < 1) throw std::invalid_argument(fmt::format("tap count {} must be at least 1", n));
    if (name == "optimal") return {spiral::search(n).tau, 1};
    if (name == "tau1") return {1, 1};
    if (name == "golden") {
        // 2 - phi turns per tap: tau = n (2 - phi) over the whole spiral.
        const long double phi = (1.0L + std::sqrt(5.0L)) / 2.0L;
        const long double turns = static_cast<long double>(n) * (2.0L - phi);
        return {std::llround(turns * static_cast<long double>(kGoldenDenominator)),
                kGoldenDenominator};
    }
    if (const std::int64_t m = fractional_denominator(name)) {
        spiral::SearchOptions options;
        options.denominator = m;
        return {spiral::search(n, options).tau, m};
    }
    throw std::invalid_argument(fmt::format("unknown pattern '{}'", name));
}

double pattern_discrepancy(std::string_view name, int n) {
    const Turns turns = pattern_turns(name, n);
    return spiral::discrepancy(n, turns.p, turns.m).value();
}

std::string format_taps_header(std::string_view prefix,
                               const std::vector<spiral::codegen::Tap>& taps, Turns turns,
                               std::string_view what) {
    std::string text =
        fmt::format("// Report pattern: {}. Written at run time by deepgi report.\n", what);
    text += fmt::format("#define {0}_NUM_TAPS {1}\n#define {0}_NUM_SPIRAL_TURNS {2:.9g}\n", prefix,
                        taps.size(), turns.value());
    text += fmt::format("#define {}_SPIRAL_TURNS_NUMERATOR {}\n", prefix, turns.p);
    text += fmt::format("#define {}_SPIRAL_TURNS_DENOMINATOR {}\n", prefix, turns.m);
    text += fmt::format("const vec2 {0}_TAP_OFFSETS[{0}_NUM_TAPS] = vec2[](\n", prefix);
    for (std::size_t i = 0; i < taps.size(); ++i) {
        text += fmt::format("    vec2({:.9g}, {:.9g}){}\n", taps[i].x, taps[i].y,
                            i + 1 < taps.size() ? "," : "");
    }
    text += fmt::format(");\nconst float {0}_TAP_ALPHAS[{0}_NUM_TAPS] = float[](\n", prefix);
    for (std::size_t i = 0; i < taps.size(); ++i) {
        text += fmt::format("    {:.9g}{}\n", taps[i].alpha, i + 1 < taps.size() ? "," : "");
    }
    return text + ");\n";
}

std::string format_discrepancy_csv(const std::vector<std::string>& patterns, int max_n) {
    std::string text = "n,pattern,p,m,discrepancy\n";
    for (int n = 1; n <= max_n; ++n) {
        for (const std::string& name : patterns) {
            const Turns turns = pattern_turns(name, n);
            text += fmt::format("{},{},{},{},{}\n", n, name, turns.p, turns.m,
                                spiral::discrepancy(n, turns.p, turns.m).value());
        }
    }
    return text;
}

}  // namespace deepgi::report
