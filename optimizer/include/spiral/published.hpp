// The table of spiral turns published with the deep G-buffer paper, and its
// comparison with the exact optimum.
//
// Mara, McGuire, Nowrouzezahrai and Luebke, "Deep G-Buffers for Stable Global
// Illumination Approximation" (HPG 2016), Listing 3: "the optimal values [of
// tau] for 1 through 99 samples", searched for the spiral pattern of McGuire,
// Mara and Luebke, "Scalable Ambient Obscurance" (HPG 2012). The listing is a
// C array of 98 integers; the paper does not say whether element 0 belongs to
// one tap or to two, and public ports read it both ways. The comparison below
// takes element i as n = i + 1 (the reading the paper's "1 through" implies)
// and says for every n whether the value ties the exact optimum there, is
// optimal only for a neighbouring n (indexed one off), or is worse.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace spiral {

// The published values in the order printed; element i is read as n = i + 1.
std::span<const int> published_turns();

enum class PublishedVerdict {
    ties_optimum,  // D(n, published) equals the minimum over integer tau
    one_off,       // worse at n, but a minimiser at n - 1 or n + 1
    worse,         // worse at n and at both neighbours
};

std::string_view to_string(PublishedVerdict verdict);

struct PublishedComparison {
    int n = 0;
    int published_tau = 0;
    std::int64_t published_scaled = 0;  // K of D(n, published): D = K / (4 n^2)
    int optimal_tau = 0;                // smallest minimiser
    std::int64_t optimal_scaled = 0;    // K of the minimum
    PublishedVerdict verdict = PublishedVerdict::worse;
    int optimal_for_n = 0;  // with one_off: the neighbouring n the value is optimal for

    std::int64_t denominator() const { return 4 * std::int64_t{n} * n; }
};

// One row per published value, n = 1 .. published_turns().size(), evaluated
// with the exact discrepancy and the exact search (jobs: as SearchOptions).
std::vector<PublishedComparison> compare_published(int jobs = 0);

}  // namespace spiral
