// The second criterion among the exact minimisers of D(n, tau) (docs/design.md,
// section 2, "Ties"): the band profile, and the rule that picks one tie.
#include <algorithm>
#include <map>
#include <stdexcept>
#include <vector>

#include "evaluate.hpp"
#include "lattice.hpp"

namespace spiral {
namespace detail {

std::vector<std::int64_t> band_profile(int n, std::int64_t tau, std::int64_t m, bool allow_lanes) {
    require_valid(n, tau, m);
    const SpiralLattice lattice(n, tau, m);
    const std::int64_t circle = lattice.circle, count_unit = 2 * circle;
    std::vector<std::int64_t> profile(static_cast<std::size_t>(n) + 1);
    // No tap: the widest empty open band over the whole circle.
    profile[0] = band_open_width(lattice.n, 0) * circle;
    if (allow_lanes && 4 * lattice.n * lattice.n * m <= kBandLaneLimit) {
        // Eight bands per pass (evaluate_bands): O(n^2 / 8) for the profile.
        BandScratch scratch;
        std::int64_t taps[8];
        for (std::int64_t first = 1; first <= lattice.n; first += 8) {
            const int count = static_cast<int>(std::min<std::int64_t>(8, lattice.n - first + 1));
            for (int j = 0; j < count; ++j) taps[j] = first + j;
            evaluate_bands(n, tau, m, taps, count, scratch,
                           profile.data() + static_cast<std::size_t>(first));
        }
        return profile;
    }
    // Taps 0 .. k-1 stand for every band of k consecutive taps (lattice
    // translation, fast.cpp); one insertion per band keeps the angles sorted,
    // so the whole profile costs O(n^2), as one full sweep does.
    BandAngles band(lattice.n);
    for (std::int64_t k = 1; k <= lattice.n; ++k) {
        band.add_tap(lattice.angular(k - 1));
        profile[static_cast<std::size_t>(k)] = band_excess(
            band.angles, band.taps_at, k, band_open_width(lattice.n, k), count_unit, circle);
    }
    return profile;
}

}  // namespace detail

std::vector<std::int64_t> band_profile(int n, std::int64_t tau, std::int64_t m) {
    return detail::band_profile(n, tau, m, true);
}

ProfileSum band_profile_sum(const std::vector<std::int64_t>& profile) {
    // Each entry is at most 4 n^2 m <= 2^60 and there are at most 2^16 of
    // them, so the sum can pass 2^63. Its high and low 30-bit parts each stay
    // below 2^46 while summed, and one carry normalises them.
    constexpr std::int64_t kMask = (std::int64_t{1} << 30) - 1;
    ProfileSum sum;
    for (const std::int64_t entry : profile) {
        sum.high += entry >> 30;
        sum.low += entry & kMask;
    }
    sum.high += sum.low >> 30;
    sum.low &= kMask;
    return sum;
}

bool tie_break_prefers(const std::vector<std::int64_t>& a, const std::vector<std::int64_t>& b) {
    return band_profile_sum(a) < band_profile_sum(b);
}

int break_tie(int n, const std::vector<int>& ties, std::int64_t m) {
    if (ties.empty()) throw std::invalid_argument("break_tie needs at least one tie");
    detail::require_valid_denominator(n, m);
    const std::int64_t nm = std::int64_t{n} * m;
    // p and nm - p are mirror images (angle y -> nm - y maps every sector to
    // one of the same kind, width and arc), so their profiles are equal and
    // one of each pair is computed.
    std::map<std::int64_t, std::vector<std::int64_t>> profiles;
    int best = 0;
    const std::vector<std::int64_t>* best_profile = nullptr;
    std::vector<int> sorted = ties;
    std::sort(sorted.begin(), sorted.end());
    for (const int p : sorted) {
        const std::int64_t key = p < nm && 2 * std::int64_t{p} > nm ? nm - p : p;
        auto found = profiles.find(key);
        if (found == profiles.end())
            found = profiles.emplace(key, detail::band_profile(n, key, m, true)).first;
        // Strictly better only: among equal profiles the smallest p stays.
        if (!best_profile || tie_break_prefers(found->second, *best_profile)) {
            best = p;
            best_profile = &found->second;
        }
    }
    return best;
}

}  // namespace spiral
