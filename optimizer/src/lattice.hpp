// Tap coordinates in half units (see optimizer.hpp), shared by the evaluators.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "spiral/optimizer.hpp"

namespace spiral::detail {

inline void require_valid(int n, int tau) {
    if (n < 1 || n > kMaxTaps)
        throw std::invalid_argument("tap count n = " + std::to_string(n) + " is outside [1, " +
                                    std::to_string(kMaxTaps) + "]");
    if (tau < 1)
        throw std::invalid_argument("turns tau = " + std::to_string(tau) + " must be at least 1");
}

// The points p_i = (2i + 1, (2i + 1) * tau mod 2n). Reducing tau modulo 2n (not n)
// keeps the points themselves; tau + n only rotates them by half a turn.
struct SpiralLattice {
    std::int64_t n;
    std::int64_t two_n;
    std::int64_t tau;  // reduced modulo 2n

    SpiralLattice(int taps, int turns)
        : n(taps),
          two_n(2 * std::int64_t{taps}),
          tau(std::int64_t{turns} % (2 * std::int64_t{taps})) {}

    std::int64_t radial(std::int64_t i) const { return 2 * i + 1; }
    std::int64_t angular(std::int64_t i) const { return ((2 * i + 1) * tau) % two_n; }
};

}  // namespace spiral::detail
