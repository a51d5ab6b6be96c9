#pragma once

#include <algorithm>
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

// Radial width of the widest open band holding `taps` consecutive taps
// (0 <= taps <= n): the canonical open band of the sweep (fast.cpp).
std::int64_t band_open_width(std::int64_t n, std::int64_t taps);

// The distinct angles of a band's taps, ascending, and how many taps each
// holds, grown one tap at a time: the sweeps over bands 1 .. n add tap k - 1
// to reach band k (lattice translation, fast.cpp).
struct BandAngles {
    std::vector<std::int64_t> angles;
    std::vector<std::int32_t> taps_at;

    explicit BandAngles(std::int64_t capacity) {
        angles.reserve(static_cast<std::size_t>(capacity));
        taps_at.reserve(static_cast<std::size_t>(capacity));
    }
    void add_tap(std::int64_t angle) {
        const auto at = std::lower_bound(angles.begin(), angles.end(), angle);
        const auto index = at - angles.begin();
        if (at != angles.end() && *at == angle) {
            taps_at[static_cast<std::size_t>(index)] += 1;
        } else {
            angles.insert(at, angle);
            taps_at.insert(taps_at.begin() + index, 1);
        }
    }
};

// The worst excess of the band of `taps` consecutive taps whose distinct
// angles (ascending) and multiplicities are given, closed and open sectors
// together; count_unit is 4nm and circle 2nm.
std::int64_t band_excess(const std::vector<std::int64_t>& angles,
                         const std::vector<std::int32_t>& taps_at, std::int64_t taps,
                         std::int64_t open_width, std::int64_t count_unit, std::int64_t circle);

// evaluate() and evaluate_bands run eight bands in 32-bit lanes when 4 n^2 m
// is at most this.
inline constexpr std::int64_t kBandLaneLimit = std::int64_t{1} << 28;

struct SpiralLattice;

// evaluate()'s value-only sweep, eight bands per pass (lanes.cpp); the same
// contract, for a lattice with 4 n^2 m <= kBandLaneLimit.
std::int64_t evaluate_in_lanes(const SpiralLattice& lattice, std::int64_t bound,
                               std::int64_t* exceeding_band, std::int64_t known_lower_bound);

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
// vector lane (lanes.cpp proves the lane values exact). When 4 n^2 m > 2^28
// the bands are evaluated one by one.
void evaluate_bands(int n, std::int64_t tau, std::int64_t m, const std::int64_t* taps, int count,
                    BandScratch& scratch, std::int64_t* excess);

// band_profile (optimizer.hpp); allow_lanes = false forces the one-band-at-a-
// time sweep that n above 8192 takes, so tests can compare the two.
std::vector<std::int64_t> band_profile(int n, std::int64_t tau, std::int64_t m, bool allow_lanes);

}  // namespace spiral::detail
