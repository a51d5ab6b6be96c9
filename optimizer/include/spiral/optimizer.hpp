// Exact annular-sector discrepancy of the spiral tap pattern, and the search
// for the number of turns that minimises it (design.md section 1).
//
// Every coordinate is measured in "half units" of 1/(2n): tap i sits at
// radial coordinate x_i = 2i + 1 and angular coordinate
// y_i = ((2i + 1) * tau) mod 2n, in a domain [0, 2n] x [0, 2n) that is periodic
// in y. A sector of radial width W and arc length L (both in half units) has
// 4n^2 * local = |4n * count - W * L|, so D(n, tau) = K / (4n^2) for an integer
// K, and everything below is integer arithmetic.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

namespace spiral {

// Largest tap count the optimizer accepts. 4n^2 needs 64 bits well before this;
// the bound keeps one exact evaluation (O(n^2)) within seconds.
inline constexpr int kMaxTaps = 65535;

// A closed or open annular sector, in half units of the tap count it was
// computed for. The arc starts at arc_start and runs arc_length forward
// (wrapping past 2n); arc_length == 2n is the whole circle. For an open sector
// the whole circle means "every angle except arc_start".
struct Sector {
    bool closed = true;
    std::int64_t radial_lo = 0;  // alpha * 2n
    std::int64_t radial_hi = 0;
    std::int64_t arc_start = 0;  // angle / (2 pi) * 2n
    std::int64_t arc_length = 0;
    std::int64_t count = 0;  // taps inside (boundary included iff closed)

    std::int64_t width() const { return radial_hi - radial_lo; }
    // Weighted area times 4n^2.
    std::int64_t scaled_area() const { return width() * arc_length; }
};

struct Discrepancy {
    int n = 0;
    int tau = 0;
    std::int64_t scaled = 0;  // K: D = K / (4 n^2)
    Sector worst;             // one sector attaining K

    std::int64_t denominator() const { return 4 * std::int64_t{n} * n; }
    double value() const { return double(scaled) / double(denominator()); }
};

// Exact D(n, tau) in O(n^2) time and O(n) memory. Requires 1 <= n <= kMaxTaps
// and tau >= 1 (tau is taken modulo n). Throws std::invalid_argument otherwise.
Discrepancy discrepancy(int n, int tau);

// The oracle: enumerates every sector whose edges lie on tap coordinates or the
// domain edges, O(n^4) with 2-D prefix counts. For tests and benchmarks only.
Discrepancy discrepancy_brute_force(int n, int tau);

struct SearchResult {
    int n = 0;
    int tau = 0;              // smallest minimiser in [1, n]
    std::vector<int> ties;    // every minimiser in [1, n], ascending
    std::int64_t scaled = 0;  // K of the minimum

    std::int64_t denominator() const { return 4 * std::int64_t{n} * n; }
    double value() const { return double(scaled) / double(denominator()); }
};

struct SearchOptions {
    int jobs = 0;  // worker threads; 0 = all hardware threads
};

// The tau in [1, n] minimising D(n, tau). Exhaustive (branch and bound never
// drops a candidate that could tie), so the result does not depend on jobs.
SearchResult search(int n, const SearchOptions& options = {});

// search() for every n in [min_n, max_n], threads spread over n. progress, if
// given, is called (serialised) after each n with (done, total).
std::vector<SearchResult> search_range(
    int min_n, int max_n, const SearchOptions& options = {},
    const std::function<void(int done, int total)>& progress = {});

}  // namespace spiral
