// A cheap, proved lower bound on K: clusters of taps on a short arc.
//
// Claim. Let q >= 1 and j >= 1 with j * q <= n - 1, and let d be the distance
// (in angular units, 0 <= d <= nm) from 0 to 2qp on the circle of length 2nm,
// i.e. d = min(r, 2nm - r) with r = 2qp mod 2nm. Then
//
//     K(n, p / m) >= 4nm (j + 1) - 2 q j^2 d.
//
// Proof. Tap i + q sits at angle y_i + 2qp, which is y_i moved by d in one
// fixed direction (the same for every i, because the move is a rotation by
// 2qp). So taps 0, q, 2q, ..., jq sit at y_0, y_0 + d, ..., y_0 + j d, read in
// that direction. The closed sector whose radial interval is [x_0, x_jq]
// (width W = 2jq) and whose arc runs from y_0 over length L = min(j d, 2nm) in
// that direction (the whole circle if j d >= 2nm) contains all j + 1 of these
// taps. K is at least the excess of any closed sector, 4nm * count - W * L, and
// here count >= j + 1 and W * L <= 2jq * j d. (With d = 0 the taps share one
// angle: L = 0 and the bound is 4nm (j + 1).)
//
// Which q. Any q gives a valid bound. A large bound needs q d small, which is
// where the denominators q_k of the convergents of p / (nm) lead: d = 2 ||q_k
// p / (nm)|| nm < 2 nm / q_{k+1}, the best approximations there are. A large
// partial quotient a_{k+1} makes q_{k+1} big, d tiny and the bound large: the
// clumping that the three-gap structure of the 1-D prefix sets describes. For
// each q the best j maximises 4nm j - 2 q d j^2, a parabola with its top at
// j = nm / (q d), so its two integer neighbours (clamped to [1, (n-1)/q]) are
// tried.
#include <algorithm>
#include <cstdint>
#include <utility>

#include "lattice.hpp"

namespace spiral {
namespace {

std::int64_t cluster_bound(const detail::SpiralLattice& lattice, std::int64_t nm, std::int64_t q) {
    const std::int64_t n = lattice.n, circle = lattice.circle, count_unit = 2 * circle;
    const std::int64_t max_j = (n - 1) / q;
    if (max_j < 1) return 0;
    const std::int64_t r = (2 * q % circle) * lattice.tau % circle;
    const std::int64_t d = std::min(r, circle - r);
    if (d == 0) return count_unit * (max_j + 1);
    auto value = [&](std::int64_t j) { return count_unit * (j + 1) - 2 * q * j * j * d; };
    const std::int64_t top = std::clamp<std::int64_t>(nm / (q * d), 1, max_j);
    std::int64_t best = value(top);
    if (top + 1 <= max_j) best = std::max(best, value(top + 1));
    return best;
}

}  // namespace

std::int64_t discrepancy_lower_bound(int n, std::int64_t tau, std::int64_t m) {
    detail::require_valid(n, tau, m);
    const detail::SpiralLattice lattice(n, tau, m);
    const std::int64_t nm = std::int64_t{n} * m;
    // K >= 4nm always: the closed sector reduced to one tap (zero width, zero
    // arc) holds at least one tap and has area 0.
    std::int64_t best = 2 * lattice.circle;
    // Convergent denominators of p / (nm): q_{-1} = 0, q_0 = 1,
    // q_{k+1} = a_{k+1} q_k + q_{k-1}.
    std::int64_t a = nm, b = lattice.tau % nm, q_prev = 0, q = 1;
    while (q <= n - 1) {
        best = std::max(best, cluster_bound(lattice, nm, q));
        if (b == 0) break;
        const std::int64_t quotient = a / b;
        a = std::exchange(b, a % b);
        q_prev = std::exchange(q, quotient * q + q_prev);
    }
    return best;
}

}  // namespace spiral
