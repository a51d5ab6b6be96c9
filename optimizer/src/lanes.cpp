// Eight bands of one candidate in one pass, in 32-bit vector lanes: the
// value-only sweep of evaluate() for n with 4 n^2 m <= 2^28, and
// evaluate_bands for the band profile. The scalar sweep, one band at a time,
// and the proof of its bands are in fast.cpp.
#include <algorithm>
#include <cstring>
#include <vector>

#include "evaluate.hpp"
#include "lattice.hpp"

namespace spiral::detail {
namespace {

// The value-only sweep spends nearly all its time in band_excess, once per
// band over a sorted array that grows by one tap per band. Bands k .. k+7 can
// share one pass over the sorted taps of band k+7: each element carries its
// tap index i, and lane j (band k + j) counts it only if i < k + j. The eight
// recurrences are independent, so they run side by side in vector registers.
//
// Why a lane gives exactly its band's worst excess. The recurrences are those
// of band_excess, but run over every element of the array: elements that the
// lane does not count (absent taps) and several elements at one angle (taps
// that share an angle are not merged). Every value a recurrence forms is the
// excess of a real sector of the lane's band: a closed arc [a, b] or an open
// arc (a, b) between two element angles, or its complement, with the count
// taken over the elements between the two in array order. For a closed arc
// that order count is at most the true count (it may miss a tap at an end
// angle), and for an open arc it is at least the true count (it may include a
// tap at an end angle): either way the value is at most the sector's true
// excess, so at most the band's worst excess. Conversely the worst sector of
// the band has its arc ends at angles of counted taps (the fact band_excess
// rests on), and choosing, among the elements at an end angle, the first for
// a closed start and an open end and the last for a closed end and an open
// start makes the order count exact. So each lane's maximum is its band's
// worst excess, the same value band_excess returns.
//
// The lanes use 32-bit integers, so this path is taken only when
// 4 n^2 m <= 2^28: every key (4nm * count - W * angle) then lies in
// [-2^28, 2^28 + 4nm] and every difference of two keys within +-2^30.

constexpr int kLanes = 8;
using Lanes = std::int32_t __attribute__((vector_size(kLanes * sizeof(std::int32_t))));
constexpr std::int32_t kLaneInf = std::int32_t{1} << 30;

// Per lane: taps in the band, closed width, open width (inputs); best closed
// and best open non-wrapping arc for each of the two widths (outputs), as in
// band_excess. Passed as plain arrays so the AVX2 clone and the generic clone
// share one calling convention.
struct LaneBands {
    alignas(32) std::int32_t taps[kLanes];
    alignas(32) std::int32_t closed_width[kLanes];
    alignas(32) std::int32_t open_width[kLanes];
    alignas(32) std::int32_t c_closed[kLanes];
    alignas(32) std::int32_t c_open[kLanes];
    alignas(32) std::int32_t o_closed[kLanes];
    alignas(32) std::int32_t o_open[kLanes];
};

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target_clones("avx2", "default")))
#endif
void scan_lanes(const std::int32_t* angle, const std::int32_t* tap, std::size_t size,
                std::int32_t count_unit, LaneBands& bands) {
    Lanes taps, closed_width, open_width;
    std::memcpy(&taps, bands.taps, sizeof taps);
    std::memcpy(&closed_width, bands.closed_width, sizeof closed_width);
    std::memcpy(&open_width, bands.open_width, sizeof open_width);
    // Lane-wise minimum and maximum: a comparison yields -1 or 0 per lane,
    // used as a mask. Written out, not as helper functions, because a function
    // taking 32-byte vectors has a different ABI with and without AVX.
#define SPIRAL_LANE_MIN(a, b) ((((a) < (b)) & (a)) | (~((a) < (b)) & (b)))
#define SPIRAL_LANE_MAX(a, b) ((((a) > (b)) & (a)) | (~((a) > (b)) & (b)))
    const Lanes zero{};
    const Lanes unit = zero + count_unit;
    // The first element starts every recurrence: no open arc ends there.
    const Lanes first = ((zero + tap[0]) < taps) & unit;
    const Lanes c_first = -closed_width * angle[0], o_first = -open_width * angle[0];
    Lanes c_min = c_first, o_min = o_first;
    Lanes c_closed = c_first + first - c_min, o_closed = o_first + first - o_min;
    Lanes c_max = c_first + first, o_max = o_first + first;
    Lanes c_open = zero + kLaneInf, o_open = zero + kLaneInf;
    Lanes base = first;  // 4nm * taps counted so far
    for (std::size_t k = 1; k < size; ++k) {
        const Lanes step = ((zero + tap[k]) < taps) & unit;
        const Lanes c_start = base - closed_width * angle[k];
        const Lanes o_start = base - open_width * angle[k];
        const Lanes c_end = c_start + step, o_end = o_start + step;
        c_min = SPIRAL_LANE_MIN(c_start, c_min);
        o_min = SPIRAL_LANE_MIN(o_start, o_min);
        const Lanes c_arc = c_end - c_min, o_arc = o_end - o_min;
        c_closed = SPIRAL_LANE_MAX(c_arc, c_closed);
        o_closed = SPIRAL_LANE_MAX(o_arc, o_closed);
        const Lanes c_gap = c_start - c_max, o_gap = o_start - o_max;
        c_open = SPIRAL_LANE_MIN(c_gap, c_open);
        o_open = SPIRAL_LANE_MIN(o_gap, o_open);
        c_max = SPIRAL_LANE_MAX(c_end, c_max);
        o_max = SPIRAL_LANE_MAX(o_end, o_max);
        base += step;
    }
#undef SPIRAL_LANE_MIN
#undef SPIRAL_LANE_MAX
    std::memcpy(bands.c_closed, &c_closed, sizeof c_closed);
    std::memcpy(bands.c_open, &c_open, sizeof c_open);
    std::memcpy(bands.o_closed, &o_closed, sizeof o_closed);
    std::memcpy(bands.o_open, &o_open, sizeof o_open);
}

// Lane j's worst excess from scan_lanes' arcs: the four kinds of sector, as in
// band_excess. `size` is how many elements the scan visited.
std::int64_t lane_excess(const LaneBands& bands, std::size_t j, std::size_t size,
                         std::int64_t circle) {
    const std::int64_t m = bands.taps[j], count_unit = 2 * circle;
    const std::int64_t closed_width = bands.closed_width[j], open_width = bands.open_width[j];
    std::int64_t worst = bands.c_closed[j];
    worst = std::max(worst, open_width * circle - count_unit * m + bands.o_closed[j]);
    if (size > 1) {
        worst = std::max(worst, count_unit * m - closed_width * circle - bands.c_open[j]);
        worst = std::max(worst, -std::int64_t{bands.o_open[j]});
    }
    return worst;
}

}  // namespace

std::int64_t evaluate_in_lanes(const SpiralLattice& lattice, std::int64_t bound,
                               std::int64_t* exceeding_band, std::int64_t known_lower_bound) {
    const std::int64_t n = lattice.n, circle = lattice.circle, count_unit = 2 * circle;
    std::int64_t best = std::max(band_open_width(n, 0) * circle, known_lower_bound);
    std::int64_t best_m = 0;
    // Every tap inserted so far, sorted by angle, with its index.
    std::vector<std::int32_t> angle, tap;
    angle.reserve(static_cast<std::size_t>(n));
    tap.reserve(static_cast<std::size_t>(n));
    LaneBands bands;
    for (std::int64_t first = 1; first <= n && best <= bound; first += kLanes) {
        const std::int64_t last = std::min(n, first + kLanes - 1);
        for (std::int64_t i = static_cast<std::int64_t>(angle.size()); i < last; ++i) {
            const auto y = static_cast<std::int32_t>(lattice.angular(i));
            const auto at = std::upper_bound(angle.begin(), angle.end(), y);
            tap.insert(tap.begin() + (at - angle.begin()), static_cast<std::int32_t>(i));
            angle.insert(at, y);
        }
        for (int j = 0; j < kLanes; ++j) {
            // Lanes past the last band repeat it; their results are ignored.
            const std::int64_t m = std::min(first + j, last);
            bands.taps[j] = static_cast<std::int32_t>(m);
            bands.closed_width[j] = static_cast<std::int32_t>(2 * (m - 1));
            bands.open_width[j] = static_cast<std::int32_t>(band_open_width(n, m));
        }
        scan_lanes(angle.data(), tap.data(), angle.size(), static_cast<std::int32_t>(count_unit),
                   bands);
        for (std::int64_t m = first; m <= last; ++m) {
            const std::int64_t worst =
                lane_excess(bands, static_cast<std::size_t>(m - first), angle.size(), circle);
            if (worst > best) {
                best = worst;
                best_m = m;
            }
        }
    }
    if (exceeding_band) *exceeding_band = best > bound ? best_m : 0;
    return best;
}

void evaluate_bands(int n, std::int64_t tau, std::int64_t m_den, const std::int64_t* taps,
                    int count, BandScratch& scratch, std::int64_t* excess) {
    const SpiralLattice lattice(n, tau, m_den);
    if (4 * lattice.n * lattice.n * m_den > kBandLaneLimit || count > kLanes) {
        for (int j = 0; j < count; ++j) excess[j] = evaluate_band(n, tau, m_den, taps[j], scratch);
        return;
    }
    const std::int64_t largest = *std::max_element(taps, taps + count);
    // Taps 0 .. largest-1 sorted by angle, each with its index: a counting
    // sort over the nm angle slots (every angle has the parity of p) when
    // there are few slots, else a sort of (angle, index) keys.
    std::vector<std::int32_t>& angle = scratch.lane_angle;
    std::vector<std::int32_t>& tap = scratch.lane_tap;
    angle.resize(static_cast<std::size_t>(largest));
    tap.resize(static_cast<std::size_t>(largest));
    const std::int64_t slots = lattice.circle / 2, step = 2 * lattice.tau % lattice.circle;
    if (slots <= 16 * lattice.n) {
        std::vector<std::int32_t>& start = scratch.bucket;
        start.assign(static_cast<std::size_t>(slots) + 1, 0);
        for (std::int64_t i = 0, y = lattice.angular(0); i < largest; ++i) {
            start[static_cast<std::size_t>(y / 2) + 1] += 1;
            y += step;
            if (y >= lattice.circle) y -= lattice.circle;
        }
        for (std::size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
        for (std::int64_t i = 0, y = lattice.angular(0); i < largest; ++i) {
            const auto at = static_cast<std::size_t>(start[static_cast<std::size_t>(y / 2)]++);
            angle[at] = static_cast<std::int32_t>(y);
            tap[at] = static_cast<std::int32_t>(i);
            y += step;
            if (y >= lattice.circle) y -= lattice.circle;
        }
    } else {
        std::vector<std::int64_t>& keys = scratch.sorted;
        keys.clear();
        for (std::int64_t i = 0, y = lattice.angular(0); i < largest; ++i) {
            keys.push_back(y << 32 | i);
            y += step;
            if (y >= lattice.circle) y -= lattice.circle;
        }
        std::sort(keys.begin(), keys.end());
        for (std::size_t k = 0; k < keys.size(); ++k) {
            angle[k] = static_cast<std::int32_t>(keys[k] >> 32);
            tap[k] = static_cast<std::int32_t>(keys[k] & 0xffffffff);
        }
    }
    LaneBands bands;
    for (int j = 0; j < kLanes; ++j) {
        // Lanes past `count` repeat the last band; their results are ignored.
        const std::int64_t m = taps[std::min(j, count - 1)];
        bands.taps[j] = static_cast<std::int32_t>(m);
        bands.closed_width[j] = static_cast<std::int32_t>(2 * (m - 1));
        bands.open_width[j] = static_cast<std::int32_t>(band_open_width(lattice.n, m));
    }
    scan_lanes(angle.data(), tap.data(), angle.size(),
               static_cast<std::int32_t>(2 * lattice.circle), bands);
    for (int j = 0; j < count; ++j)
        excess[j] = lane_excess(bands, static_cast<std::size_t>(j), angle.size(), lattice.circle);
}

}  // namespace spiral::detail
