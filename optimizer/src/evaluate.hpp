#pragma once

#include <cstdint>
#include <vector>

#include "spiral/optimizer.hpp"

namespace spiral::detail {

// K for (n, tau / m), or some value above `bound` as soon as K is known to
// exceed it. Writes one worst sector when asked (only meaningful if K <= bound)
// and, when asked, the tap count of the band that first exceeded the bound
// (0 if none did). known_lower_bound, a proved lower bound on K, lets the
// value-only sweep skip bands that cannot exceed it (ignored when a sector is
// asked for). The value-only sweep runs eight bands per pass in 32-bit lanes
// when 4 n^2 m <= 2^28, else one band at a time; allow_lanes = false forces
// the latter (so tests can compare the two). The arguments must already be
// valid (require_valid).
std::int64_t evaluate(int n, std::int64_t tau, std::int64_t m, std::int64_t bound,
                      Sector* worst_sector, std::int64_t* exceeding_band = nullptr,
                      std::int64_t known_lower_bound = 0, bool allow_lanes = true);

struct BandScratch {
    std::vector<std::int64_t> sorted, angles;
    std::vector<std::int32_t> taps_at, bucket, lane_angle, lane_tap;
};

// The worst excess over the closed and open sectors of the single band that
// holds `taps` consecutive taps (1 <= taps <= n): a lower bound on K, computed
// from scratch in O(taps log taps) or O(nm) for small m, so bands can be
// probed in any order.
std::int64_t evaluate_band(int n, std::int64_t tau, std::int64_t m, std::int64_t taps,
                           BandScratch& scratch);

// Up to eight bands of one candidate at once: excess[j] = evaluate_band(n,
// tau, m, taps[j]) for j < count (1 <= count <= 8), in one pass over the
// taps of the largest band sorted by angle, each band in its own 32-bit
// vector lane (fast.cpp proves the lane values exact). When 4 n^2 m > 2^28
// the bands are evaluated one by one.
void evaluate_bands(int n, std::int64_t tau, std::int64_t m, const std::int64_t* taps, int count,
                    BandScratch& scratch, std::int64_t* excess);

}  // namespace spiral::detail
