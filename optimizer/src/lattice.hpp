// Tap coordinates (see optimizer.hpp), shared by the evaluators.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "spiral/optimizer.hpp"

namespace spiral::detail {

inline void require_valid_taps(int n) {
    if (n < 1 || n > kMaxTaps)
        throw std::invalid_argument("tap count n = " + std::to_string(n) + " is outside [1, " +
                                    std::to_string(kMaxTaps) + "]");
}

inline void require_valid_denominator(int n, std::int64_t m) {
    require_valid_taps(n);
    if (m < 1)
        throw std::invalid_argument("turn denominator m = " + std::to_string(m) +
                                    " must be at least 1");
    // 4 n^2 m <= 2^60 without overflowing on the way: compare m with the quotient.
    const std::int64_t four_n_squared = 4 * std::int64_t{n} * n;
    if (m > kMaxScaledDenominator / four_n_squared)
        throw std::invalid_argument("4 n^2 m for n = " + std::to_string(n) +
                                    ", m = " + std::to_string(m) +
                                    " exceeds the 64-bit limit 2^60 (m must be at most " +
                                    std::to_string(kMaxScaledDenominator / four_n_squared) + ")");
}

inline void require_valid(int n, std::int64_t tau, std::int64_t m) {
    require_valid_denominator(n, m);
    if (tau < 1)
        throw std::invalid_argument("turns numerator tau = " + std::to_string(tau) +
                                    " must be at least 1");
}

// The points p_i = (2i + 1, (2i + 1) * p mod 2nm) for the turns p / m.
// Reducing p modulo 2nm (not nm) keeps the points themselves; p + nm only
// rotates them by half a turn.
struct SpiralLattice {
    std::int64_t n;
    std::int64_t two_n;   // radial extent
    std::int64_t circle;  // 2nm: the whole circle in angular units
    std::int64_t tau;     // the numerator p, reduced modulo 2nm

    SpiralLattice(int taps, std::int64_t turns, std::int64_t m = 1)
        : n(taps),
          two_n(2 * std::int64_t{taps}),
          circle(2 * std::int64_t{taps} * m),
          tau(turns % (2 * std::int64_t{taps} * m)) {}

    std::int64_t radial(std::int64_t i) const { return 2 * i + 1; }
    // (2i + 1) < 2n and tau < 2nm, so the product stays below 4 n^2 m.
    std::int64_t angular(std::int64_t i) const { return ((2 * i + 1) * tau) % circle; }
};

}  // namespace spiral::detail
