// The deep G-buffer paper's tau table (Listing 3) against the exact optimum;
// see published.hpp for the source and the reading of its index.
#include "spiral/published.hpp"

#include <array>

#include "spiral/optimizer.hpp"

namespace spiral {
namespace {

// Mara et al. 2016, Listing 3, in the order printed (98 values).
constexpr std::array<int, 98> published_table = {
    1,  1,  2,  3,  2,  5,  2,  3,  2,  3,  3,  5,  5,  3,  4,  7,  5,  5,  7,  9,
    8,  5,  5,  7,  7,  7,  8,  5,  8,  11, 12, 7,  10, 13, 8,  11, 8,  7,  14, 11,
    11, 13, 12, 13, 19, 17, 13, 11, 18, 19, 11, 11, 14, 17, 21, 15, 16, 17, 18, 13,
    17, 11, 17, 19, 18, 25, 18, 19, 19, 29, 21, 19, 27, 31, 29, 21, 18, 17, 29, 31,
    31, 23, 18, 25, 26, 25, 23, 19, 34, 19, 27, 21, 25, 39, 29, 17, 21, 27,
};

}  // namespace

std::span<const int> published_turns() {
    return published_table;
}

std::string_view to_string(PublishedVerdict verdict) {
    switch (verdict) {
        case PublishedVerdict::ties_optimum:
            return "ties the optimum";
        case PublishedVerdict::one_off:
            return "indexed one off";
        case PublishedVerdict::worse:
            return "worse";
    }
    return "?";
}

std::vector<PublishedComparison> compare_published(int jobs) {
    const int count = int(published_table.size());
    // The optimum for one n beyond the table too, for the one-off check.
    const std::vector<SearchResult> optimum = search_range(1, count + 1, SearchOptions{jobs, 1});
    std::vector<PublishedComparison> rows;
    for (int n = 1; n <= count; ++n) {
        PublishedComparison row;
        row.n = n;
        row.published_tau = published_table[std::size_t(n - 1)];
        row.published_scaled = discrepancy_scaled(n, row.published_tau);
        row.optimal_tau = optimum[std::size_t(n - 1)].tau;
        row.optimal_scaled = optimum[std::size_t(n - 1)].scaled;
        if (row.published_scaled == row.optimal_scaled) {
            row.verdict = PublishedVerdict::ties_optimum;
        } else {
            row.verdict = PublishedVerdict::worse;
            for (int neighbour : {n - 1, n + 1}) {
                if (neighbour < 1) continue;
                if (discrepancy_scaled(neighbour, row.published_tau) ==
                    optimum[std::size_t(neighbour - 1)].scaled) {
                    row.verdict = PublishedVerdict::one_off;
                    row.optimal_for_n = neighbour;
                    break;
                }
            }
        }
        rows.push_back(row);
    }
    return rows;
}

}  // namespace spiral
