// Exact D(n, tau / m) in O(n^2), generic in the turn denominator m.
//
// Two facts reduce the O(n^4) sectors of the brute force:
//
// 1. Lattice translation. Moving from tap i to tap i + k adds 2k to the radial
//    coordinate and 2k * p to the angular one, for every tap at once. A
//    radial band is therefore characterised, up to a rotation that changes no
//    count, by how many consecutive taps it holds. The best closed band with m
//    taps is [x_i, x_{i+m-1}] (width 2(m - 1)); the best open one is
//    (x_{i-1}, x_{i+m}) (width 2(m + 1)) while such taps exist, else it reaches
//    a domain edge: width 2n - 1 for m = n - 1 and 2n for m = n. Narrower open
//    bands through a domain edge hold a translate of the same taps and lose.
//    So only n + 1 bands remain, each holding the taps 0 .. m-1 of the lattice.
//
// 2. Within a band, the worst arc is a cyclic maximum-subarray problem over
//    the taps sorted by angle. A wrapping arc is the complement of a
//    non-wrapping arc of the opposite kind (closed <-> open), so one linear pass
//    that tracks the best closed and the best open non-wrapping arc answers
//    both kinds. The band's distinct angles are kept in a sorted array (one
//    insertion per band, merging taps that share an angle when gcd(p, nm) > 1),
//    so band k costs O(k), not O(n): a candidate that fails in an early band
//    costs next to nothing.
//
// Bands are visited with growing tap count k, adding one tap each, so the
// search can stop as soon as one band already exceeds the bound (branch and
// bound). In the comments below n and the count multiplier 4n stand for the
// general 4nm, and 2n on the angle axis for the circle 2nm.
//
// The value-only sweep runs eight bands per pass in vector lanes where the
// keys fit 32 bits (lanes.cpp); the scalar sweep here is its reference, and
// the one that reports a worst sector.
#include <algorithm>
#include <array>
#include <limits>
#include <vector>

#include "evaluate.hpp"
#include "lattice.hpp"

namespace spiral {
namespace detail {
namespace {

constexpr std::int64_t kInf = std::numeric_limits<std::int64_t>::max() / 4;

// The worst arcs of one band for one radial width W, non-wrapping only.
//   best_closed: max over closed arcs [p_s, p_e] of 4n * count - W * (p_e - p_s)
//   best_open:   min over open arcs (p_s, p_e) of 4n * count - W * (p_e - p_s)
struct ArcScan {
    std::int64_t width;
    std::int64_t min_start_key = kInf, min_start_pos = 0, min_start_before = 0;
    std::int64_t max_start_key = -kInf, max_start_pos = 0, max_start_through = 0;
    std::int64_t best_closed = -kInf, closed_start = 0, closed_end = 0, closed_count = 0;
    std::int64_t best_open = kInf, open_start = 0, open_end = 0, open_count = 0;
    bool has_open = false;

    explicit ArcScan(std::int64_t w) : width(w) {}

    // A slot at angle `pos` holding `here` taps, `before` taps at smaller angles.
    void visit(std::int64_t four_n, std::int64_t pos, std::int64_t before, std::int64_t here) {
        const std::int64_t through = before + here;
        const std::int64_t start_key = four_n * before - width * pos;
        if (start_key < min_start_key) {
            min_start_key = start_key;
            min_start_pos = pos;
            min_start_before = before;
        }
        const std::int64_t closed = four_n * through - width * pos - min_start_key;
        if (closed > best_closed) {
            best_closed = closed;
            closed_start = min_start_pos;
            closed_end = pos;
            closed_count = through - min_start_before;
        }
        if (max_start_key > -kInf) {
            const std::int64_t open = four_n * before - width * pos - max_start_key;
            if (open < best_open) {
                best_open = open;
                open_start = max_start_pos;
                open_end = pos;
                open_count = before - max_start_through;
                has_open = true;
            }
        }
        const std::int64_t end_key = four_n * through - width * pos;
        if (end_key > max_start_key) {
            max_start_key = end_key;
            max_start_pos = pos;
            max_start_through = through;
        }
    }
};

struct BandWorst {
    std::int64_t excess = -kInf;
    Sector arc;  // radial fields filled in later
};

// Closed sectors of a band of m taps and width W: the best non-wrapping closed
// arc, or the complement of the best non-wrapping open arc.
BandWorst worst_closed(const ArcScan& scan, std::int64_t four_n, std::int64_t two_n,
                       std::int64_t m) {
    BandWorst worst;
    worst.excess = scan.best_closed;
    worst.arc = {
        true, 0, 0, scan.closed_start, scan.closed_end - scan.closed_start, scan.closed_count};
    if (scan.has_open) {
        const std::int64_t length = two_n - (scan.open_end - scan.open_start);
        const std::int64_t excess = four_n * m - scan.width * two_n - scan.best_open;
        if (excess > worst.excess) {
            worst.excess = excess;
            worst.arc = {true, 0, 0, scan.open_end, length, m - scan.open_count};
        }
    }
    return worst;
}

// Open sectors: the best non-wrapping open arc, or the complement of the best
// non-wrapping closed arc (with s == e, the whole circle less one angle).
BandWorst worst_open(const ArcScan& scan, std::int64_t four_n, std::int64_t two_n, std::int64_t m) {
    BandWorst worst;
    const std::int64_t length = two_n - (scan.closed_end - scan.closed_start);
    worst.excess = scan.width * two_n - four_n * m + scan.best_closed;
    worst.arc = {false, 0, 0, scan.closed_end, length, m - scan.closed_count};
    if (scan.has_open && -scan.best_open > worst.excess) {
        worst.excess = -scan.best_open;
        worst.arc = {false,          0, 0, scan.open_start, scan.open_end - scan.open_start,
                     scan.open_count};
    }
    return worst;
}

// The worst closed and the worst open sector of the band of m taps whose
// distinct angles (ascending) and multiplicities are given.
std::array<BandWorst, 2> scan_band(const std::vector<std::int64_t>& angles,
                                   const std::vector<std::int32_t>& taps_at, std::int64_t m,
                                   std::int64_t open_width, std::int64_t count_unit,
                                   std::int64_t circle) {
    ArcScan closed_scan(2 * (m - 1)), open_scan(open_width);
    std::int64_t before = 0;
    for (std::size_t k = 0; k < angles.size(); ++k) {
        const std::int64_t here = taps_at[k], pos = angles[k];
        closed_scan.visit(count_unit, pos, before, here);
        open_scan.visit(count_unit, pos, before, here);
        before += here;
    }
    return {worst_closed(closed_scan, count_unit, circle, m),
            worst_open(open_scan, count_unit, circle, m)};
}

}  // namespace

std::int64_t band_open_width(std::int64_t n, std::int64_t m) {
    return m <= n - 2 ? 2 * m + 2 : (m == n - 1 ? 2 * n - 1 : 2 * n);
}

// scan_band without the sector bookkeeping, for callers that need only the
// value: the same recurrences as ArcScan, tracking the keys alone.
std::int64_t band_excess(const std::vector<std::int64_t>& angles,
                         const std::vector<std::int32_t>& taps_at, std::int64_t m,
                         std::int64_t open_width, std::int64_t count_unit, std::int64_t circle) {
    const std::int64_t closed_width = 2 * (m - 1);
    // Per width: smallest start key, best closed arc, largest end key, best open arc.
    std::int64_t c_min = kInf, c_closed = -kInf, c_max = -kInf, c_open = kInf;
    std::int64_t o_min = kInf, o_closed = -kInf, o_max = -kInf, o_open = kInf;
    std::int64_t before = 0;
    const std::size_t size = angles.size();
    for (std::size_t k = 0; k < size; ++k) {
        const std::int64_t pos = angles[k];
        const std::int64_t through = before + taps_at[k];
        const std::int64_t before_key = count_unit * before, through_key = count_unit * through;
        const std::int64_t c_pos = closed_width * pos, o_pos = open_width * pos;
        c_min = std::min(c_min, before_key - c_pos);
        o_min = std::min(o_min, before_key - o_pos);
        c_closed = std::max(c_closed, through_key - c_pos - c_min);
        o_closed = std::max(o_closed, through_key - o_pos - o_min);
        // An open arc ends at a later angle than the one it starts after; c_max
        // still holds only earlier angles here (kept as -kInf until then).
        if (c_max > -kInf) {
            c_open = std::min(c_open, before_key - c_pos - c_max);
            o_open = std::min(o_open, before_key - o_pos - o_max);
        }
        c_max = std::max(c_max, through_key - c_pos);
        o_max = std::max(o_max, through_key - o_pos);
        before = through;
    }
    std::int64_t worst = c_closed;  // closed sectors, non-wrapping
    // Open sectors, wrapping: the complement of the best closed non-wrapping arc.
    worst = std::max(worst, open_width * circle - count_unit * m + o_closed);
    if (c_max > -kInf && size > 1) {
        // Closed wrapping: the complement of the best open non-wrapping arc.
        worst = std::max(worst, count_unit * m - closed_width * circle - c_open);
        worst = std::max(worst, -o_open);  // open sectors, non-wrapping
    }
    return worst;
}

std::int64_t evaluate_band(int n, std::int64_t tau, std::int64_t m_den, std::int64_t taps,
                           BandScratch& scratch) {
    const SpiralLattice lattice(n, tau, m_den);
    scratch.angles.clear();
    scratch.taps_at.clear();
    // Every angle has the parity of p (the circle 2nm is even), so angle / 2
    // is an exact slot in [0, nm). Bucket by slot when there are few slots,
    // else sort.
    const std::int64_t slots = lattice.circle / 2;
    if (slots <= 16 * lattice.n) {
        std::vector<std::int32_t>& bucket = scratch.bucket;
        bucket.assign(static_cast<std::size_t>(slots), 0);
        // Consecutive taps differ by 2p in angle: step instead of a division per tap.
        const std::int64_t step = 2 * lattice.tau % lattice.circle;
        for (std::int64_t i = 0, y = lattice.angular(0); i < taps; ++i) {
            bucket[static_cast<std::size_t>(y / 2)] += 1;
            y += step;
            if (y >= lattice.circle) y -= lattice.circle;
        }
        const std::int64_t parity = lattice.tau % 2;
        for (std::int64_t slot = 0; slot < slots; ++slot) {
            if (bucket[static_cast<std::size_t>(slot)] == 0) continue;
            scratch.angles.push_back(2 * slot + parity);
            scratch.taps_at.push_back(bucket[static_cast<std::size_t>(slot)]);
        }
    } else {
        std::vector<std::int64_t>& sorted = scratch.sorted;
        sorted.clear();
        for (std::int64_t i = 0; i < taps; ++i) sorted.push_back(lattice.angular(i));
        std::sort(sorted.begin(), sorted.end());
        for (const std::int64_t angle : sorted) {
            if (!scratch.angles.empty() && scratch.angles.back() == angle) {
                scratch.taps_at.back() += 1;
            } else {
                scratch.angles.push_back(angle);
                scratch.taps_at.push_back(1);
            }
        }
    }
    return band_excess(scratch.angles, scratch.taps_at, taps, band_open_width(lattice.n, taps),
                       2 * lattice.circle, lattice.circle);
}

std::int64_t evaluate(int n, std::int64_t tau, std::int64_t m_den, std::int64_t bound,
                      Sector* worst_sector, std::int64_t* exceeding_band,
                      std::int64_t known_lower_bound, bool allow_lanes) {
    const SpiralLattice lattice(n, tau, m_den);
    if (allow_lanes && !worst_sector && 4 * lattice.n * lattice.n * m_den <= kBandLaneLimit)
        return evaluate_in_lanes(lattice, bound, exceeding_band, known_lower_bound);
    const std::int64_t circle = lattice.circle;
    const std::int64_t count_unit = 2 * circle;  // 4nm
    auto open_width = [&](std::int64_t m) { return band_open_width(lattice.n, m); };

    // The empty open band: the whole circle, nothing inside.
    std::int64_t best = open_width(0) * circle;
    std::int64_t best_m = 0;
    BandWorst best_band{best, Sector{false, 0, 0, 0, circle, 0}};

    // A known lower bound on K (0 if none) joins the running maximum: any band
    // skipped below it is then no larger than K, and K >= it is attained.
    if (!worst_sector && known_lower_bound > best) best = known_lower_bound;
    std::int64_t last_excess = 0, last_m = 0;

    BandAngles band(lattice.n);
    for (std::int64_t m = 1; m <= lattice.n && best <= bound; ++m) {
        band.add_tap(lattice.angular(m - 1));
        if (!worst_sector) {
            // Adding one tap changes a band's worst excess by at most 4nm:
            // for any fixed arc, the count grows by 0 or 1 (worth 4nm) and
            // the width by at most 2 (worth at most 2 * 2nm), in opposite
            // directions for closed and open sectors. So band m cannot beat
            // `best` while last_excess + 4nm (m - last_m) <= best, and its
            // scan can be skipped without changing the maximum.
            if (last_m > 0 && last_excess + count_unit * (m - last_m) <= best) continue;
            const std::int64_t excess =
                band_excess(band.angles, band.taps_at, m, open_width(m), count_unit, circle);
            last_excess = excess;
            last_m = m;
            if (excess > best) {
                best = excess;
                best_m = m;
            }
            continue;
        }
        for (const BandWorst& band :
             scan_band(band.angles, band.taps_at, m, open_width(m), count_unit, circle)) {
            if (band.excess > best) {
                best = band.excess;
                best_band = band;
                best_m = m;
            }
        }
    }
    if (exceeding_band) *exceeding_band = best > bound ? best_m : 0;

    if (worst_sector) {
        // Place the canonical band (taps 0 .. m-1) where it really fits.
        Sector sector = best_band.arc;
        const std::int64_t m = best_m;
        if (sector.closed) {
            sector.radial_lo = 1;
            sector.radial_hi = 2 * m - 1;
        } else if (m <= lattice.n - 2) {
            // (x_0, x_{m+1}) holds taps 1 .. m: the canonical taps moved by one.
            sector.radial_lo = 1;
            sector.radial_hi = 2 * m + 3;
            sector.arc_start = (sector.arc_start + 2 * lattice.tau) % circle;
        } else {
            sector.radial_lo = 0;
            sector.radial_hi = open_width(m);
        }
        *worst_sector = sector;
    }
    return best;
}

}  // namespace detail

Discrepancy discrepancy(int n, std::int64_t tau, std::int64_t m) {
    detail::require_valid(n, tau, m);
    Discrepancy result{n, tau, 0, {}, m};
    result.scaled =
        detail::evaluate(n, tau, m, std::numeric_limits<std::int64_t>::max(), &result.worst);
    return result;
}

}  // namespace spiral

namespace spiral {

std::int64_t discrepancy_scaled(int n, std::int64_t tau, std::int64_t m) {
    detail::require_valid(n, tau, m);
    return detail::evaluate(n, tau, m, std::numeric_limits<std::int64_t>::max(), nullptr);
}

}  // namespace spiral
