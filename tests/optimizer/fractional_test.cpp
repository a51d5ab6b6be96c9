// Fractional turns tau = p / m and the cluster lower bound: the generic
// evaluator against the brute-force oracle, scaling and mirror properties,
// the search over p against a brute-force minimisation, and input checks.
//
// Units: radial 1/(2n), angular 1/(2nm), D = K / (4 n^2 m) (docs/design.md, section 3).
#include <catch2/catch.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "spiral/optimizer.hpp"
#include "tap_oracle.hpp"

using spiral::discrepancy;
using spiral::discrepancy_brute_force;
using spiral::discrepancy_lower_bound;

namespace {

// The definition, evaluated by the oracle for every p in [1, nm].
spiral::SearchResult minimise_by_brute_force(int n, std::int64_t m) {
    spiral::SearchResult result{n, 0, {}, -1, m};
    for (std::int64_t p = 1; p <= n * m; ++p) {
        const auto k = discrepancy_brute_force(n, p, m).scaled;
        if (result.scaled < 0 || k < result.scaled) {
            result.scaled = k;
            result.ties.clear();
        }
        if (k == result.scaled) result.ties.push_back(static_cast<int>(p));
    }
    // Which minimiser is tau is the tie-break's business (tie_break_test.cpp).
    result.tau = spiral::break_tie(n, result.ties, m);
    return result;
}

}  // namespace

TEST_CASE("fractional: fast evaluator equals the brute force for every p, n <= 12",
          "[discrepancy][fractional][oracle]") {
    const int n = GENERATE(range(1, 13));
    const std::int64_t m = GENERATE(2, 3, 4, 8);
    for (std::int64_t p = 1; p <= n * m; ++p) {
        INFO("n = " << n << ", p = " << p << ", m = " << m);
        const auto fast = discrepancy(n, p, m);
        const auto oracle = discrepancy_brute_force(n, p, m);
        REQUIRE(fast.scaled == oracle.scaled);
        CHECK(fast.denominator() == 4 * std::int64_t{n} * n * m);
        CHECK(spiral::test::recounted_excess(n, p, fast.worst, m) == fast.scaled);
        CHECK(spiral::test::recounted_excess(n, p, oracle.worst, m) == oracle.scaled);
    }
}

TEST_CASE("fractional: the value-only scan equals the brute force", "[discrepancy][oracle]") {
    // discrepancy_scaled() is what the search runs; it shares no scan code
    // with the brute force and only the recurrences with discrepancy().
    for (int n = 1; n <= 36; ++n)
        for (std::int64_t m : {1, 2, 5})
            for (std::int64_t p = 1; p <= n * m; p += (m == 1 ? 1 : 3)) {
                INFO("n = " << n << ", p = " << p << ", m = " << m);
                CHECK(spiral::discrepancy_scaled(n, p, m) ==
                      discrepancy_brute_force(n, p, m).scaled);
            }
}

TEST_CASE("fractional: refining the denominator scales K and keeps D", "[fractional][property]") {
    // p / m = (k p) / (k m) is the same spiral; only the angular unit shrinks
    // k-fold, so every arc length and 4nm grow k-fold and K = k K.
    for (int n = 1; n <= 30; ++n)
        for (std::int64_t p = 1; p <= 2 * n; ++p)
            for (std::int64_t k : {2, 3, 5}) {
                INFO("n = " << n << ", p = " << p << " / 2, k = " << k);
                CHECK(discrepancy(n, k * p, 2 * k).scaled == k * discrepancy(n, p, 2).scaled);
            }
    // And m = 1 is the integer evaluator.
    for (int n = 1; n <= 30; ++n)
        for (int tau = 1; tau <= n; ++tau)
            CHECK(discrepancy(n, 4 * tau, 4).scaled == 4 * discrepancy(n, tau).scaled);
}

TEST_CASE("fractional: D(p / m) = D((nm - p) / m) and D is periodic in n turns",
          "[fractional][property]") {
    for (int n = 1; n <= 40; ++n)
        for (std::int64_t m : {2, 3, 8})
            for (std::int64_t p = 1; p < n * m; ++p) {
                INFO("n = " << n << ", p = " << p << ", m = " << m);
                const auto k = discrepancy(n, p, m).scaled;
                CHECK(k == discrepancy(n, n * m - p, m).scaled);
                CHECK(k == discrepancy(n, p + n * m, m).scaled);
            }
}

TEST_CASE("fractional: n = 16, m = 8 beats the integer optimum with tau = 49/8",
          "[fractional][search][oracle]") {
    // Independent check: the brute force over every p in [1, 128] finds the
    // minimum at p = 49 and its mirror 128 - 49 = 79 (equal band profiles, so
    // the smaller stays) with
    // K = 1420, D = 1420 / 8192 = 0.173340, below the integer optimum
    // D(16, 7) = 192 / 1024 = 0.1875 (= 1536 / 8192 in eighths).
    const auto expected = minimise_by_brute_force(16, 8);
    CHECK(expected.tau == 49);
    CHECK(expected.scaled == 1420);
    CHECK(expected.ties == std::vector<int>{49, 79});
    const auto found = spiral::search(16, spiral::SearchOptions{2, 8});
    CHECK(found.m == 8);
    CHECK(found.tau == expected.tau);
    CHECK(found.scaled == expected.scaled);
    CHECK(found.ties == expected.ties);
    CHECK(found.value() == Approx(0.173340).margin(5e-7));
    const auto integer = spiral::search(16);
    CHECK(integer.tau == 7);
    CHECK(integer.scaled == 192);
}

TEST_CASE("fractional: search equals a brute-force minimisation for small n and m",
          "[fractional][search][oracle]") {
    const int n = GENERATE(range(1, 11));
    const std::int64_t m = GENERATE(2, 3, 4);
    const auto expected = minimise_by_brute_force(n, m);
    for (int jobs : {1, 2, 3}) {
        const auto found = spiral::search(n, spiral::SearchOptions{jobs, m});
        INFO("n = " << n << ", m = " << m << ", jobs = " << jobs);
        CHECK(found.scaled == expected.scaled);
        CHECK(found.tau == expected.tau);
        CHECK(found.ties == expected.ties);
    }
}

TEST_CASE("fractional: results do not depend on the thread count", "[fractional][threads]") {
    const auto one = spiral::search_range(1, 64, spiral::SearchOptions{1, 8});
    const auto three = spiral::search_range(1, 64, spiral::SearchOptions{3, 8});
    REQUIRE(one.size() == three.size());
    for (std::size_t k = 0; k < one.size(); ++k) {
        INFO("n = " << one[k].n);
        CHECK(one[k].scaled == three[k].scaled);
        CHECK(one[k].ties == three[k].ties);
    }
}

TEST_CASE("fractional: bad denominators and overflowing combinations are rejected",
          "[fractional][errors]") {
    CHECK_THROWS_AS(discrepancy(8, 3, 0), std::invalid_argument);
    CHECK_THROWS_AS(discrepancy(8, 3, -2), std::invalid_argument);
    CHECK_THROWS_AS(spiral::search(8, spiral::SearchOptions{1, 0}), std::invalid_argument);
    CHECK_THROWS_AS(spiral::search_range(1, 8, spiral::SearchOptions{1, -1}),
                    std::invalid_argument);
    // 4 n^2 m must stay within 2^60: at n = 65535 that allows m <= 67110912.
    const std::int64_t n = spiral::kMaxTaps;
    const std::int64_t max_m = spiral::kMaxScaledDenominator / (4 * n * n);
    CHECK_NOTHROW(discrepancy_lower_bound(spiral::kMaxTaps, 1, max_m));
    CHECK_THROWS_WITH(discrepancy(spiral::kMaxTaps, 1, max_m + 1),
                      Catch::Contains("2^60") && Catch::Contains(std::to_string(max_m)));
}

TEST_CASE("bounds: the cluster bound never exceeds K, every tau and n <= 200",
          "[bounds][property]") {
    // The bound is proved in bounds.cpp; this checks the proof and the code
    // against the exact K of every integer candidate the search can meet.
    for (int n = 1; n <= 200; ++n)
        for (int tau = 1; tau <= n; ++tau) {
            const auto bound = discrepancy_lower_bound(n, tau);
            const auto exact = discrepancy(n, tau).scaled;
            if (bound > exact)
                FAIL("n = " << n << ", tau = " << tau << ": bound " << bound << " > K " << exact);
        }
    SUCCEED();
}

TEST_CASE("bounds: the cluster bound never exceeds K for fractional turns",
          "[bounds][fractional][property]") {
    for (int n = 1; n <= 48; ++n)
        for (std::int64_t m : {2, 3, 4, 8})
            for (std::int64_t p = 1; p <= n * m; ++p) {
                const auto bound = discrepancy_lower_bound(n, p, m);
                const auto exact = discrepancy(n, p, m).scaled;
                if (bound > exact)
                    FAIL("n = " << n << ", p = " << p << ", m = " << m << ": bound " << bound
                                << " > K " << exact);
            }
    SUCCEED();
}

TEST_CASE("bounds: the cluster bound is tight where all taps share an angle",
          "[bounds][property]") {
    // tau = n puts every tap on one ray: the closed band of all n taps with a
    // zero-length arc gives 4nm * n, the largest K any pattern can have.
    for (int n = 1; n <= 50; ++n)
        for (std::int64_t m : {1, 2, 8}) {
            INFO("n = " << n << ", m = " << m);
            CHECK(discrepancy_lower_bound(n, n * m, m) == 4 * std::int64_t{n} * n * m);
            CHECK(discrepancy(n, n * m, m).scaled == 4 * std::int64_t{n} * n * m);
        }
    // tau = 1 (one turn) clusters the first taps: the bound rejects it well
    // above the optimum for every n >= 8.
    for (int n = 8; n <= 200; ++n) {
        INFO("n = " << n);
        CHECK(discrepancy_lower_bound(n, 1) > spiral::search(n).scaled);
    }
}

TEST_CASE("fractional: a finer denominator never does worse", "[fractional][search][property]") {
    // p / m = 2p / 2m, so the search over m = 2k covers every candidate of
    // m = k: its minimum K (in units 2x finer) is at most twice the coarser one.
    for (int n = 1; n <= 64; ++n) {
        std::int64_t previous = -1;
        for (std::int64_t m : {1, 2, 4, 8}) {
            const auto r = spiral::search(n, spiral::SearchOptions{1, m});
            INFO("n = " << n << ", m = " << m);
            if (previous >= 0) CHECK(r.scaled <= 2 * previous);
            previous = r.scaled;
        }
    }
}
