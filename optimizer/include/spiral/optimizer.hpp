// Exact annular-sector discrepancy of the spiral tap pattern, and the search
// for the number of turns that minimises it (docs/design.md, sections 1 to 3).
//
// Every coordinate is measured in "half units" of 1/(2n): tap i sits at
// radial coordinate x_i = 2i + 1 and angular coordinate
// y_i = ((2i + 1) * tau) mod 2n, in a domain [0, 2n] x [0, 2n) that is periodic
// in y. A sector of radial width W and arc length L (both in half units) has
// 4n^2 * local = |4n * count - W * L|, so D(n, tau) = K / (4n^2) for an integer
// K, and everything below is integer arithmetic.
//
// Fractional turns tau = p / m (docs/design.md, section 3) refine the angular unit
// to 1/(2nm): tap i sits at angle ((2i + 1) * p) mod 2nm, a sector's arc length
// L is counted in that unit, and 4n^2 m * local = |4nm * count - W * L|, so
// D = K / (4 n^2 m). m = 1 is the integer case. Wherever a turn count appears
// below as an integer `tau` together with a denominator m, it is the numerator
// p of tau = p / m.
#pragma once

#include <compare>
#include <cstdint>
#include <functional>
#include <vector>

namespace spiral {

// Largest tap count the optimizer accepts. 4n^2 needs 64 bits well before this;
// the bound keeps one exact evaluation (O(n^2)) within seconds.
inline constexpr int kMaxTaps = 65535;

// Largest 4 n^2 m accepted: every intermediate value of an evaluation (counts
// times 4nm, widths times arc lengths, and differences of two such) then stays
// far inside 64-bit signed arithmetic.
inline constexpr std::int64_t kMaxScaledDenominator = std::int64_t{1} << 60;

// A closed or open annular sector. Radial coordinates are in units of 1/(2n)
// of the radius, angular ones in units of 1/(2nm) of a turn. The arc starts at
// arc_start and runs arc_length forward (wrapping past 2nm); arc_length == 2nm
// is the whole circle. For an open sector the whole circle means "every angle
// except arc_start".
struct Sector {
    bool closed = true;
    std::int64_t radial_lo = 0;  // alpha * 2n
    std::int64_t radial_hi = 0;
    std::int64_t arc_start = 0;  // angle / (2 pi) * 2n
    std::int64_t arc_length = 0;
    std::int64_t count = 0;  // taps inside (boundary included iff closed)

    std::int64_t width() const { return radial_hi - radial_lo; }
    // Weighted area times 4n^2 m.
    std::int64_t scaled_area() const { return width() * arc_length; }
};

struct Discrepancy {
    int n = 0;
    std::int64_t tau = 0;     // numerator p: the spiral makes tau / m turns
    std::int64_t scaled = 0;  // K: D = K / (4 n^2 m)
    Sector worst;             // one sector attaining K
    std::int64_t m = 1;       // denominator of the turns

    std::int64_t denominator() const { return 4 * std::int64_t{n} * n * m; }
    double value() const { return double(scaled) / double(denominator()); }
};

// Exact D(n, tau / m) in O(n^2) time and O(n) memory. Requires
// 1 <= n <= kMaxTaps, tau >= 1, m >= 1 and 4 n^2 m <= kMaxScaledDenominator.
// Throws std::invalid_argument otherwise.
Discrepancy discrepancy(int n, std::int64_t tau, std::int64_t m = 1);

// K of discrepancy(n, tau, m) alone, without the worst sector: the value the
// search computes (a leaner scan). Same requirements and exceptions.
std::int64_t discrepancy_scaled(int n, std::int64_t tau, std::int64_t m = 1);

// The oracle: enumerates every sector whose edges lie on tap coordinates or the
// domain edges, O(n^4) with 2-D prefix counts (and O(n^2 m) memory). For tests
// and benchmarks only.
Discrepancy discrepancy_brute_force(int n, std::int64_t tau, std::int64_t m = 1);

// A proved lower bound on K of discrepancy(n, tau, m), in O(log n): clusters
// of taps that a short arc of a narrow band holds (see bounds.cpp). The search
// rejects a candidate whose bound exceeds the best K found without scanning it.
std::int64_t discrepancy_lower_bound(int n, std::int64_t tau, std::int64_t m = 1);

// The worst local error of each radial band (docs/design.md, section 2,
// "Ties"): entry k, 0 <= k <= n, is the largest 4 n^2 m * local error over
// the sectors whose radial extent holds exactly k tap radii (a closed sector
// counts the radii in [a, b], an open one those in (a, b)). Its largest entry
// is K. O(n^2) time, O(n) memory; same requirements and exceptions as
// discrepancy().
std::vector<std::int64_t> band_profile(int n, std::int64_t tau, std::int64_t m = 1);

// The oracle for band_profile: every sector of discrepancy_brute_force, filed
// by the tap radii it holds. O(n^4); for tests only.
std::vector<std::int64_t> band_profile_brute_force(int n, std::int64_t tau, std::int64_t m = 1);

// The sum of a band profile's entries, high * 2^30 + low with 0 <= low < 2^30:
// exact, though it can pass 2^63 for the largest n and m (entries are
// non-negative and at most 2^60, at most 2^16 of them). Compares as the sum.
struct ProfileSum {
    std::int64_t high = 0;
    std::int64_t low = 0;
    auto operator<=>(const ProfileSum&) const = default;
};
ProfileSum band_profile_sum(const std::vector<std::int64_t>& profile);

// The tie-break among exact minimisers (docs/design.md, section 2, "Ties"):
// profile a is preferred to profile b when its sum is smaller, that is when
// the worst local errors of the radial bands are smaller on average.
bool tie_break_prefers(const std::vector<std::int64_t>& a, const std::vector<std::int64_t>& b);

// The tie-break winner among `ties`, numerators p of minimisers of D(n, p / m)
// (any order, not empty): the p whose band profile is preferred, the smallest
// p among equal profiles. Mirror images p and nm - p always have equal
// profiles. Throws std::invalid_argument for an empty list or invalid n, m.
int break_tie(int n, const std::vector<int>& ties, std::int64_t m = 1);

struct SearchResult {
    int n = 0;
    int tau = 0;              // the minimiser p in [1, nm] break_tie picks (turns p / m)
    std::vector<int> ties;    // every minimiser in [1, nm], ascending
    std::int64_t scaled = 0;  // K of the minimum
    std::int64_t m = 1;       // denominator of the turns searched

    std::int64_t denominator() const { return 4 * std::int64_t{n} * n * m; }
    double value() const { return double(scaled) / double(denominator()); }
};

// Largest n * m the search accepts: every candidate numerator fits an int.
inline constexpr std::int64_t kMaxSearchCandidates = std::int64_t{1} << 30;

struct SearchOptions {
    int jobs = 0;                  // worker threads; 0 = all hardware threads
    std::int64_t denominator = 1;  // m: search the turns p / m, p in [1, nm]
};

// The p in [1, nm] minimising D(n, p / m), m = options.denominator; m = 1 is
// the integer search over tau in [1, n]. Every minimiser is in ties; tau is
// the one break_tie picks. Exhaustive (branch and bound never
// drops a candidate that could tie), so the result does not depend on jobs.
// Throws std::invalid_argument for n outside [1, kMaxTaps], m < 1,
// 4 n^2 m > kMaxScaledDenominator or n m > kMaxSearchCandidates.
SearchResult search(int n, const SearchOptions& options = {});

// search() for every n in [min_n, max_n], threads spread over n. progress, if
// given, is called (serialised) after each n with (done, total).
std::vector<SearchResult> search_range(
    int min_n, int max_n, const SearchOptions& options = {},
    const std::function<void(int done, int total)>& progress = {});

}  // namespace spiral
