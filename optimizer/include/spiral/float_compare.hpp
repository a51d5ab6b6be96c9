// A double-precision evaluator of the spiral's sector discrepancy D(n, tau),
// written only to compare against the exact integer optimizer (the search
// never uses it): it does what a straightforward floating-point
// implementation would do, so that the places where rounding changes the
// chosen number of turns can be listed. compare_float_search() lists them;
// tests/bench/float_tau_compare and the report (docs/report.md) print it.
//
// Taps sit at radius fraction r_i = (i + 0.5) / n and angle (in turns)
// frac((i + 0.5) * tau / n), both computed in double. Taps are merged into one
// angle only when their doubles compare equal, and a sector's local
// discrepancy is |count / n - width * arc| in double. The sectors searched are
// the same family as the exact evaluator's (bands of consecutive taps, worst
// closed and open arc per band by a maximum-subarray scan), so any difference
// from the exact result comes from rounding alone.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace spiral_float {

// D(n, tau) in double; stops early (returning a value > bound) once a band
// already exceeds bound, which cannot change an argmin taken with strict <.
inline double discrepancy(int n, int tau, double bound = std::numeric_limits<double>::infinity()) {
    const double inv_n = 1.0 / double(n);
    auto radius = [&](int i) { return (double(i) + 0.5) * inv_n; };
    auto angle = [&](int i) {
        const double turns = (double(i) + 0.5) * double(tau) / double(n);
        return turns - std::floor(turns);
    };
    // Widths of the closed and open bands holding k consecutive taps.
    auto closed_width = [&](int k) { return radius(k - 1) - radius(0); };
    auto open_width = [&](int k) {
        if (k <= n - 2) return radius(k + 1) - radius(0);
        return k == n - 1 ? 1.0 - radius(0) : 1.0;
    };

    double best = open_width(0);  // empty open band over the whole circle
    std::vector<double> angles;
    std::vector<int> taps_at;
    for (int k = 1; k <= n && best <= bound; ++k) {
        const double a = angle(k - 1);
        const auto at = std::lower_bound(angles.begin(), angles.end(), a);
        const auto index = at - angles.begin();
        if (at != angles.end() && *at == a) {
            taps_at[std::size_t(index)] += 1;
        } else {
            angles.insert(at, a);
            taps_at.insert(taps_at.begin() + index, 1);
        }
        for (const bool closed_band : {true, false}) {
            const double w = closed_band ? closed_width(k) : open_width(k);
            // Non-wrapping arcs from slot s to slot e: closed [a_s, a_e] and open
            // (a_s, a_e). Keys as in a maximum-subarray scan.
            double min_start = std::numeric_limits<double>::infinity();
            double max_end = -std::numeric_limits<double>::infinity();
            double best_closed = -std::numeric_limits<double>::infinity();
            double best_open = std::numeric_limits<double>::infinity();
            int before = 0;
            for (std::size_t s = 0; s < angles.size(); ++s) {
                const int through = before + taps_at[s];
                const double pos = angles[s];
                min_start = std::min(min_start, before * inv_n - w * pos);
                best_closed = std::max(best_closed, through * inv_n - w * pos - min_start);
                if (s > 0) best_open = std::min(best_open, before * inv_n - w * pos - max_end);
                max_end = std::max(max_end, through * inv_n - w * pos);
                before = through;
            }
            const double all = k * inv_n;
            if (closed_band) {
                best = std::max(best, best_closed);  // too many taps, non-wrapping
                // Wrapping closed arc: complement of an open non-wrapping one.
                if (angles.size() > 1) best = std::max(best, all - w - best_open);
            } else {
                // Wrapping open arc: complement of a closed non-wrapping one.
                best = std::max(best, w - all + best_closed);
                if (angles.size() > 1) best = std::max(best, -best_open);
            }
        }
    }
    return best;
}

struct Pick {
    int tau = 0;
    double value = 0;
};

// The tau in [1, n] with the smallest double D, the first on ties.
inline Pick search(int n) {
    Pick pick{1, discrepancy(n, 1)};
    for (int tau = 2; tau <= n; ++tau) {
        const double d = discrepancy(n, tau, pick.value);
        if (d < pick.value) pick = {tau, d};
    }
    return pick;
}

// One n of the comparison: the exact search's tau and K (D = K / 4n^2), the
// double search's tau and the exact K of that tau.
struct Choice {
    int n = 0;
    int exact_tau = 0;
    std::int64_t exact_k = 0;
    int float_tau = 0;
    std::int64_t float_tau_exact_k = 0;
    std::int64_t denominator = 0;  // 4n^2

    bool differs() const { return float_tau != exact_tau; }
    // Another exact minimiser that rounding ranked first (no quality lost).
    bool tie() const { return float_tau_exact_k == exact_k; }
};

// Both searches for every n in [1, max_n], on `jobs` threads (0: all). The
// double search evaluates every tau in [1, n] at O(n^2) each (less with its
// early stop): on the shared 2-core machine 0.1 s for max_n = 64, 1 s for
// 256, 95 to 130 s for 1024.
std::vector<Choice> compare_float_search(int max_n, int jobs = 0);

}  // namespace spiral_float
