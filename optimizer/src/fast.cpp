// Exact D(n, tau) in O(n^2).
//
// Two facts reduce the O(n^4) sectors of the brute force:
//
// 1. Lattice translation. Moving from tap i to tap i + k adds 2k to the radial
//    coordinate and 2k * tau to the angular one, for every tap at once. A
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
//    both kinds. Taps are bucketed by angle (n slots), which sorts them for
//    free and merges taps that share an angle when gcd(tau, n) > 1.
//
// Bands are visited with growing m, adding one tap each, so the search can
// stop as soon as one band already exceeds the bound (branch and bound).
#include <algorithm>
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

}  // namespace

std::int64_t evaluate(int n, int tau, std::int64_t bound, Sector* worst_sector) {
    const SpiralLattice lattice(n, tau);
    const std::int64_t two_n = lattice.two_n, four_n = 4 * lattice.n;
    auto open_width = [&](std::int64_t m) {
        return m <= lattice.n - 2 ? 2 * m + 2 : (m == lattice.n - 1 ? two_n - 1 : two_n);
    };

    // The empty open band: the whole circle, nothing inside.
    std::int64_t best = open_width(0) * two_n;
    std::int64_t best_m = 0;
    BandWorst best_band{best, Sector{false, 0, 0, 0, two_n, 0}};

    // Slot = angle / 2: all angles share the parity of tau, so this is exact.
    std::vector<std::int32_t> taps_at_slot(static_cast<std::size_t>(lattice.n), 0);
    const std::int64_t parity = lattice.tau % 2;
    for (std::int64_t m = 1; m <= lattice.n && best <= bound; ++m) {
        taps_at_slot[static_cast<std::size_t>(lattice.angular(m - 1) / 2)] += 1;

        ArcScan closed_scan(2 * (m - 1)), open_scan(open_width(m));
        std::int64_t before = 0;
        for (std::int64_t slot = 0; slot < lattice.n; ++slot) {
            const std::int64_t here = taps_at_slot[static_cast<std::size_t>(slot)];
            if (here == 0) continue;
            const std::int64_t pos = 2 * slot + parity;
            closed_scan.visit(four_n, pos, before, here);
            open_scan.visit(four_n, pos, before, here);
            before += here;
        }
        for (const BandWorst& band : {worst_closed(closed_scan, four_n, two_n, m),
                                      worst_open(open_scan, four_n, two_n, m)}) {
            if (band.excess > best) {
                best = band.excess;
                best_band = band;
                best_m = m;
            }
        }
    }

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
            sector.arc_start = (sector.arc_start + 2 * lattice.tau) % two_n;
        } else {
            sector.radial_lo = 0;
            sector.radial_hi = open_width(m);
        }
        *worst_sector = sector;
    }
    return best;
}

}  // namespace detail

Discrepancy discrepancy(int n, int tau) {
    detail::require_valid(n, tau);
    Discrepancy result{n, tau, 0, {}};
    result.scaled =
        detail::evaluate(n, tau, std::numeric_limits<std::int64_t>::max(), &result.worst);
    return result;
}

}  // namespace spiral
