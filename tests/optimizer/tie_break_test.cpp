// The tie-break among exact minimisers (docs/design.md, section 2, "Ties"):
// the band profile against the brute force, the rule against an oracle written
// from its definition, and the search's tau always one of its ties.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "evaluate.hpp"
#include "spiral/optimizer.hpp"

namespace {

using Profile = std::vector<std::int64_t>;

// The rule, from its definition: the smaller sum of the band profile. For
// n <= 40 the sums fit 64 bits easily.
bool oracle_prefers(const Profile& a, const Profile& b) {
    std::int64_t sum_a = 0, sum_b = 0;
    for (const std::int64_t entry : a) sum_a += entry;
    for (const std::int64_t entry : b) sum_b += entry;
    return sum_a < sum_b;
}

// Every minimiser by a full evaluation of every p in [1, nm] (the evaluator
// equals the brute force for every tau with n <= 40: discrepancy_test.cpp),
// then the one the rule prefers among their brute-force profiles, the
// smallest p on equal ones. Uses neither the search nor break_tie.
spiral::SearchResult break_tie_by_brute_force(int n, std::int64_t m = 1) {
    spiral::SearchResult result{n, 0, {}, -1, m};
    for (std::int64_t p = 1; p <= n * m; ++p) {
        const auto k = spiral::discrepancy_scaled(n, p, m);
        if (result.scaled < 0 || k < result.scaled) {
            result.scaled = k;
            result.ties.clear();
        }
        if (k == result.scaled) result.ties.push_back(static_cast<int>(p));
    }
    Profile best;
    for (const int p : result.ties) {
        Profile profile = spiral::band_profile_brute_force(n, p, m);
        if (result.tau == 0 || oracle_prefers(profile, best)) {
            result.tau = p;
            best = std::move(profile);
        }
    }
    return result;
}

// The inverse of tau modulo n (gcd(tau, n) = 1), by trying every residue.
int inverse_mod(int tau, int n) {
    for (int t = 1; t < n; ++t)
        if (tau * t % n == 1) return t;
    return n == 1 ? 0 : -1;
}

}  // namespace

TEST_CASE("ties: the band profile equals the brute force for every tau, n <= 16",
          "[ties][oracle]") {
    const int n = GENERATE(range(1, 17));
    for (int tau = 1; tau <= n; ++tau) {
        INFO("n = " << n << ", tau = " << tau);
        const Profile profile = spiral::band_profile(n, tau);
        CHECK(profile == spiral::band_profile_brute_force(n, tau));
        CHECK(profile == spiral::detail::band_profile(n, tau, 1, false));
        // Its largest entry is K.
        CHECK(*std::max_element(profile.begin(), profile.end()) ==
              spiral::discrepancy_scaled(n, tau));
    }
}

TEST_CASE("ties: the band profile equals the brute force for fractional turns",
          "[ties][oracle][fractional]") {
    const std::int64_t m = GENERATE(2, 3, 4);
    for (int n = 1; n <= 9; ++n)
        for (std::int64_t p = 1; p <= n * m; ++p) {
            INFO("n = " << n << ", p = " << p << ", m = " << m);
            CHECK(spiral::band_profile(n, p, m) == spiral::band_profile_brute_force(n, p, m));
        }
}

TEST_CASE("ties: the lane and one-band profiles agree, and mirror images have equal profiles",
          "[ties][property]") {
    const int n = GENERATE(17, 40, 64, 99, 128, 200);
    for (int tau = 1; tau <= n; ++tau) {
        INFO("n = " << n << ", tau = " << tau);
        const Profile profile = spiral::band_profile(n, tau);
        CHECK(profile == spiral::detail::band_profile(n, tau, 1, false));
        if (tau < n) CHECK(profile == spiral::band_profile(n, n - tau));
    }
}

TEST_CASE("ties: search picks what the rule picks among the brute-force minimisers, n <= 40",
          "[ties][oracle][search]") {
    const int n = GENERATE(range(1, 41));
    const auto expected = break_tie_by_brute_force(n);
    const auto found = spiral::search(n);
    INFO("n = " << n);
    CHECK(found.scaled == expected.scaled);
    CHECK(found.ties == expected.ties);  // every minimiser, ascending, as before
    CHECK(found.tau == expected.tau);
    CHECK(spiral::break_tie(n, found.ties) == expected.tau);
}

TEST_CASE("ties: the rule against the brute force for fractional turns", "[ties][oracle]") {
    const std::int64_t m = GENERATE(2, 4);
    for (int n = 1; n <= 10; ++n) {
        INFO("n = " << n << ", m = " << m);
        const auto expected = break_tie_by_brute_force(n, m);
        spiral::SearchOptions options;
        options.denominator = m;
        const auto found = spiral::search(n, options);
        CHECK(found.ties == expected.ties);
        CHECK(found.tau == expected.tau);
    }
}

TEST_CASE("ties: the chosen tau is always one of the ties, whatever their order",
          "[ties][property]") {
    for (const auto& result : spiral::search_range(1, 300, {2, 1})) {
        INFO("n = " << result.n);
        REQUIRE(!result.ties.empty());
        CHECK(std::is_sorted(result.ties.begin(), result.ties.end()));
        CHECK(std::find(result.ties.begin(), result.ties.end(), result.tau) != result.ties.end());
        CHECK(spiral::discrepancy_scaled(result.n, result.tau) == result.scaled);
        std::vector<int> reversed(result.ties.rbegin(), result.ties.rend());
        CHECK(spiral::break_tie(result.n, reversed) == result.tau);
    }
    for (const std::int64_t m : {2, 8})
        for (const auto& result : spiral::search_range(1, 64, {2, m})) {
            INFO("n = " << result.n << ", m = " << m);
            CHECK(std::find(result.ties.begin(), result.ties.end(), result.tau) !=
                  result.ties.end());
        }
}

// Exchanging the roles of radius and angle maps the lattice of tau to that of
// its inverse modulo n (docs/design.md, section 2, "Ties"). D does not see
// the exchange, so with the mirror image every tau has up to four spirals of
// equal D, and the tie sets are unions of these orbits.
TEST_CASE("ties: D is the same for tau and its inverse modulo n", "[ties][oracle]") {
    SECTION("the brute force, every tau prime to n, n <= 30") {
        for (int n = 2; n <= 30; ++n)
            for (int tau = 1; tau < n; ++tau) {
                if (std::gcd(tau, n) != 1) continue;
                INFO("n = " << n << ", tau = " << tau);
                CHECK(spiral::discrepancy_brute_force(n, tau).scaled ==
                      spiral::discrepancy_brute_force(n, inverse_mod(tau, n)).scaled);
            }
    }
    SECTION("the evaluator, every tau prime to n, n <= 200") {
        for (int n = 31; n <= 200; ++n)
            for (int tau = 1; tau < n; ++tau) {
                if (std::gcd(tau, n) != 1) continue;
                INFO("n = " << n << ", tau = " << tau);
                CHECK(spiral::discrepancy_scaled(n, tau) ==
                      spiral::discrepancy_scaled(n, inverse_mod(tau, n)));
            }
    }
    SECTION("every tie set is closed under the mirror and the inverse, n <= 200") {
        int two_pairs_to_64 = 0;
        std::vector<int> four_pairs;
        for (const auto& result : spiral::search_range(3, 200)) {
            INFO("n = " << result.n);
            for (const int tau : result.ties) {
                REQUIRE(std::gcd(tau, result.n) == 1);
                const auto has = [&](int t) {
                    return std::find(result.ties.begin(), result.ties.end(), t) !=
                           result.ties.end();
                };
                CHECK(has(result.n - tau));
                CHECK(has(inverse_mod(tau, result.n)));
            }
            if (result.ties.size() == 4 && result.n <= 64) ++two_pairs_to_64;
            if (result.ties.size() == 8) four_pairs.push_back(result.n);
        }
        // Two pairs tie at 38 n of 3..64 (the tie study's rows), each an
        // orbit of four; two orbits of four tie only at these n up to 200.
        CHECK(two_pairs_to_64 == 38);
        CHECK(four_pairs == std::vector<int>{100, 162, 167});
    }
}

TEST_CASE("ties: hard cases", "[ties][hard]") {
    // n = 6: the only minimisers are one turn either way, mirror images of
    // each other, so their profiles are equal and the smaller stays.
    const auto six = spiral::search(6);
    CHECK(six.ties == std::vector<int>{1, 5});
    CHECK(six.scaled == 64);
    CHECK(spiral::band_profile(6, 1) == spiral::band_profile(6, 5));
    CHECK(six.tau == 1);
    // n = 49: the first n whose pick is not the smallest minimiser. The pairs
    // {18, 31} and {19, 30} tie at K = 656; 19's profile sums to less.
    const auto forty_nine = spiral::search(49);
    CHECK(forty_nine.ties == std::vector<int>{18, 19, 30, 31});
    CHECK(spiral::band_profile_sum(spiral::band_profile(49, 19)) <
          spiral::band_profile_sum(spiral::band_profile(49, 18)));
    CHECK(forty_nine.tau == 19);
    // The default tap counts keep their turns: n = 11 picks 3 of {3, 4, 7, 8},
    // n = 19 picks 7 of {7, 8, 11, 12}.
    CHECK(spiral::search(11).tau == 3);
    CHECK(spiral::search(19).tau == 7);
    // The sum is exact beyond 64 bits: 2^16 entries of 2^60.
    const Profile large(std::size_t{1} << 16, std::int64_t{1} << 60);
    CHECK(spiral::band_profile_sum(large) == spiral::ProfileSum{std::int64_t{1} << 46, 0});
    CHECK(spiral::band_profile_sum({(std::int64_t{1} << 30) - 1, 1, 5}) ==
          spiral::ProfileSum{1, 5});
    // One candidate is its own answer; an empty list is an error.
    CHECK(spiral::break_tie(9, {7}) == 7);
    CHECK_THROWS_AS(spiral::break_tie(9, {}), std::invalid_argument);
    CHECK_THROWS_AS(spiral::band_profile(0, 1), std::invalid_argument);
    CHECK_THROWS_AS(spiral::band_profile(5, 0), std::invalid_argument);
}
