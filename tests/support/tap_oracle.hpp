// Direct counting of taps in a sector, straight from the definition in
// design.md 1.2; used to check the sectors that evaluators report.
#pragma once

#include <cstdint>
#include <cstdlib>

#include "spiral/optimizer.hpp"

namespace spiral::test {

inline std::int64_t taps_in_sector(int n, int tau, const Sector& s) {
    const std::int64_t two_n = 2 * std::int64_t{n};
    std::int64_t count = 0;
    for (std::int64_t i = 0; i < n; ++i) {
        const std::int64_t x = 2 * i + 1;
        const std::int64_t y = ((2 * i + 1) * (tau % two_n)) % two_n;
        const std::int64_t offset = ((y - s.arc_start) % two_n + two_n) % two_n;
        const bool radial_in = s.closed ? (s.radial_lo <= x && x <= s.radial_hi)
                                        : (s.radial_lo < x && x < s.radial_hi);
        const bool angular_in = s.closed ? (s.arc_length >= two_n || offset <= s.arc_length)
                                         : (offset > 0 && offset < s.arc_length);
        count += radial_in && angular_in;
    }
    return count;
}

// |4n * count - W * L| for the sector, counted independently of the evaluator.
inline std::int64_t recounted_excess(int n, int tau, const Sector& s) {
    const std::int64_t count = taps_in_sector(n, tau, s);
    const std::int64_t excess = 4 * std::int64_t{n} * count - s.scaled_area();
    return s.closed ? excess : -excess;
}

}  // namespace spiral::test
