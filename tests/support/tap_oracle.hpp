// Direct counting of taps in a sector, straight from the definition in
// docs/design.md, section 2; used to check the sectors that evaluators report.
#pragma once

#include <cstdint>
#include <cstdlib>

#include "spiral/optimizer.hpp"

namespace spiral::test {

// Angles in units of 1/(2nm) of a turn for the turns tau / m (m = 1: integer).
inline std::int64_t taps_in_sector(int n, std::int64_t tau, const Sector& s, std::int64_t m = 1) {
    const std::int64_t circle = 2 * std::int64_t{n} * m;
    std::int64_t count = 0;
    for (std::int64_t i = 0; i < n; ++i) {
        const std::int64_t x = 2 * i + 1;
        const std::int64_t y = ((2 * i + 1) * (tau % circle)) % circle;
        const std::int64_t offset = ((y - s.arc_start) % circle + circle) % circle;
        const bool radial_in = s.closed ? (s.radial_lo <= x && x <= s.radial_hi)
                                        : (s.radial_lo < x && x < s.radial_hi);
        const bool angular_in = s.closed ? (s.arc_length >= circle || offset <= s.arc_length)
                                         : (offset > 0 && offset < s.arc_length);
        count += radial_in && angular_in;
    }
    return count;
}

// |4nm * count - W * L| for the sector, counted independently of the evaluator.
inline std::int64_t recounted_excess(int n, std::int64_t tau, const Sector& s, std::int64_t m = 1) {
    const std::int64_t count = taps_in_sector(n, tau, s, m);
    const std::int64_t excess = 4 * std::int64_t{n} * m * count - s.scaled_area();
    return s.closed ? excess : -excess;
}

}  // namespace spiral::test
