// The oracle: every sector whose edges lie on tap coordinates or the domain
// edges, counted with a 2-D prefix table. Deliberately uses none of the
// lattice structure that the fast evaluator relies on.
#include <algorithm>
#include <vector>

#include "lattice.hpp"

namespace spiral {
namespace {

class PrefixCounts {
public:
    explicit PrefixCounts(const detail::SpiralLattice& lattice)
        : cols_(lattice.circle + 1), rows_(lattice.two_n + 2), table_(cols_ * rows_, 0) {
        // table_(x, y) = number of taps with radial < x and angular < y.
        std::vector<std::int64_t> grid(cols_ * rows_, 0);
        for (std::int64_t i = 0; i < lattice.n; ++i)
            grid[index(lattice.radial(i) + 1, lattice.angular(i) + 1)] += 1;
        for (std::int64_t x = 1; x < rows_; ++x)
            for (std::int64_t y = 1; y < cols_; ++y)
                table_[index(x, y)] = grid[index(x, y)] + table_[index(x - 1, y)] +
                                      table_[index(x, y - 1)] - table_[index(x - 1, y - 1)];
        circle_ = lattice.circle;
    }

    // Taps with radial in [x_lo, x_hi] and angular among the `length` positions
    // starting at y_start (cyclic). Empty if x_lo > x_hi or length <= 0.
    std::int64_t count(std::int64_t x_lo, std::int64_t x_hi, std::int64_t y_start,
                       std::int64_t length) const {
        x_lo = std::max<std::int64_t>(x_lo, 0);
        x_hi = std::min(x_hi, rows_ - 2);
        if (x_lo > x_hi || length <= 0) return 0;
        length = std::min(length, circle_);
        y_start %= circle_;
        const std::int64_t y_end = y_start + length;  // exclusive
        if (y_end <= circle_) return rect(x_lo, x_hi, y_start, y_end);
        return rect(x_lo, x_hi, y_start, circle_) + rect(x_lo, x_hi, 0, y_end - circle_);
    }

private:
    std::int64_t index(std::int64_t x, std::int64_t y) const { return x * cols_ + y; }
    // radial in [x_lo, x_hi], angular in [y_lo, y_hi)
    std::int64_t rect(std::int64_t x_lo, std::int64_t x_hi, std::int64_t y_lo,
                      std::int64_t y_hi) const {
        return table_[index(x_hi + 1, y_hi)] - table_[index(x_lo, y_hi)] -
               table_[index(x_hi + 1, y_lo)] + table_[index(x_lo, y_lo)];
    }

    std::int64_t cols_, rows_, circle_ = 0;
    std::vector<std::int64_t> table_;
};

// Calls visit(sector, excess) for every closed and open sector whose edges lie
// on tap coordinates or the domain edges, excess being 4 n^2 m times its
// signed local error (positive: too many taps for a closed sector, too few
// for an open one; the other sign never attains the maximum).
template <class Visit>
void for_each_sector(const detail::SpiralLattice& lattice, Visit&& visit) {
    const PrefixCounts counts(lattice);
    const std::int64_t two_n = lattice.two_n, circle = lattice.circle, four_nm = 2 * circle;

    std::vector<std::int64_t> radial_edges{0, two_n};
    std::vector<std::int64_t> angular_edges;
    for (std::int64_t i = 0; i < lattice.n; ++i) {
        radial_edges.push_back(lattice.radial(i));
        angular_edges.push_back(lattice.angular(i));
    }
    std::sort(radial_edges.begin(), radial_edges.end());
    std::sort(angular_edges.begin(), angular_edges.end());
    angular_edges.erase(std::unique(angular_edges.begin(), angular_edges.end()),
                        angular_edges.end());

    auto consider = [&](const Sector& sector) {
        visit(sector, sector.closed ? four_nm * sector.count - sector.scaled_area()
                                    : sector.scaled_area() - four_nm * sector.count);
    };
    for (std::size_t lo = 0; lo < radial_edges.size(); ++lo) {
        for (std::size_t hi = lo; hi < radial_edges.size(); ++hi) {
            const std::int64_t a = radial_edges[lo], b = radial_edges[hi];
            for (const std::int64_t start : angular_edges) {
                // Arc lengths reaching every other edge, plus the whole circle.
                std::vector<std::int64_t> lengths{circle};
                for (const std::int64_t end : angular_edges)
                    lengths.push_back(((end - start) % circle + circle) % circle);
                for (const std::int64_t length : lengths) {
                    Sector closed{true, a, b, start, length, counts.count(a, b, start, length + 1)};
                    consider(closed);
                    if (a < b && length > 0) {
                        Sector open{false,  a,
                                    b,      start,
                                    length, counts.count(a + 1, b - 1, start + 1, length - 1)};
                        consider(open);
                    }
                }
            }
        }
    }
}

// Tap radii 2i + 1 (all odd values in [0, 2n]) within [lo, hi].
std::int64_t radii_within(std::int64_t lo, std::int64_t hi) {
    return lo > hi ? 0 : (hi + 1) / 2 - lo / 2;
}

}  // namespace

Discrepancy discrepancy_brute_force(int n, std::int64_t tau, std::int64_t m) {
    detail::require_valid(n, tau, m);
    const detail::SpiralLattice lattice(n, tau, m);
    Discrepancy result{n, tau, -1, {}, m};
    for_each_sector(lattice, [&](const Sector& sector, std::int64_t excess) {
        if (excess > result.scaled) {
            result.scaled = excess;
            result.worst = sector;
        }
    });
    return result;
}

std::vector<std::int64_t> band_profile_brute_force(int n, std::int64_t tau, std::int64_t m) {
    detail::require_valid(n, tau, m);
    const detail::SpiralLattice lattice(n, tau, m);
    std::vector<std::int64_t> profile(static_cast<std::size_t>(n) + 1, -1);
    for_each_sector(lattice, [&](const Sector& sector, std::int64_t excess) {
        const std::int64_t radii = sector.closed
                                       ? radii_within(sector.radial_lo, sector.radial_hi)
                                       : radii_within(sector.radial_lo + 1, sector.radial_hi - 1);
        std::int64_t& worst = profile[static_cast<std::size_t>(radii)];
        worst = std::max(worst, excess);
    });
    return profile;
}

}  // namespace spiral
