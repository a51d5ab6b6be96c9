// search(): the exhaustive minimiser against the brute force, ties, and
// independence from the thread count.
#include <catch2/catch.hpp>

#include <algorithm>
#include <vector>

#include "spiral/optimizer.hpp"

namespace {

// The definition, evaluated by the oracle for every tau in [1, n].
spiral::SearchResult minimise_by_brute_force(int n) {
    spiral::SearchResult result{n, 0, {}, -1};
    for (int tau = 1; tau <= n; ++tau) {
        const auto k = spiral::discrepancy_brute_force(n, tau).scaled;
        if (result.scaled < 0 || k < result.scaled) {
            result.scaled = k;
            result.ties.clear();
        }
        if (k == result.scaled) result.ties.push_back(tau);
    }
    // Which minimiser is tau is the tie-break's business (tie_break_test.cpp).
    result.tau = spiral::break_tie(n, result.ties);
    return result;
}

}  // namespace

TEST_CASE("search: search finds the brute-force minimum and every tie", "[search][oracle]") {
    const int n = GENERATE(range(1, 33));
    const auto expected = minimise_by_brute_force(n);
    const auto found = spiral::search(n);
    INFO("n = " << n);
    CHECK(found.n == n);
    CHECK(found.scaled == expected.scaled);
    CHECK(found.tau == expected.tau);
    CHECK(found.ties == expected.ties);
}

TEST_CASE("search: search agrees with an exhaustive fast scan for larger n", "[search]") {
    // Branch and bound may stop a candidate early; a full evaluation of every
    // tau must find the same minimum and the same ties.
    const int n = GENERATE(64, 89, 99, 144, 233, 256, 300);
    std::int64_t best = -1;
    std::vector<int> ties;
    for (int tau = 1; tau <= n; ++tau) {
        const auto k = spiral::discrepancy(n, tau).scaled;
        if (best < 0 || k < best) {
            best = k;
            ties.clear();
        }
        if (k == best) ties.push_back(tau);
    }
    const auto found = spiral::search(n);
    INFO("n = " << n);
    CHECK(found.scaled == best);
    CHECK(found.ties == ties);
    CHECK(found.tau == spiral::break_tie(n, ties));
}

TEST_CASE("search: ties come in mirror pairs", "[search][property]") {
    for (int n = 2; n <= 99; ++n) {
        const auto r = spiral::search(n);
        INFO("n = " << n);
        for (int tau : r.ties)
            if (tau < n) CHECK(std::binary_search(r.ties.begin(), r.ties.end(), n - tau));
        CHECK(std::is_sorted(r.ties.begin(), r.ties.end()));
    }
}

TEST_CASE("search: results do not depend on the thread count", "[search][threads]") {
    const auto one = spiral::search_range(1, 160, spiral::SearchOptions{1});
    const auto three = spiral::search_range(1, 160, spiral::SearchOptions{3});
    REQUIRE(one.size() == three.size());
    for (std::size_t k = 0; k < one.size(); ++k) {
        INFO("n = " << one[k].n);
        CHECK(one[k].n == three[k].n);
        CHECK(one[k].scaled == three[k].scaled);
        CHECK(one[k].ties == three[k].ties);
    }
    for (int n : {377, 500, 610}) {
        const auto serial = spiral::search(n, spiral::SearchOptions{1});
        const auto parallel = spiral::search(n, spiral::SearchOptions{4});
        INFO("n = " << n);
        CHECK(serial.scaled == parallel.scaled);
        CHECK(serial.ties == parallel.ties);
    }
}

TEST_CASE("search: search_range reports progress once per n", "[search]") {
    int calls = 0, last_done = 0;
    const auto results =
        spiral::search_range(5, 24, spiral::SearchOptions{2}, [&](int done, int total) {
            ++calls;
            CHECK(total == 20);
            CHECK(done == last_done + 1);
            last_done = done;
        });
    CHECK(calls == 20);
    REQUIRE(results.size() == 20);
    CHECK(results.front().n == 5);
    CHECK(results.back().n == 24);
}

TEST_CASE("search: search rejects invalid ranges", "[search][errors]") {
    CHECK_THROWS_AS(spiral::search(0), std::invalid_argument);
    CHECK_THROWS_AS(spiral::search(spiral::kMaxTaps + 1), std::invalid_argument);
    CHECK_THROWS_AS(spiral::search_range(0, 5), std::invalid_argument);
    CHECK_THROWS_AS(spiral::search_range(6, 5), std::invalid_argument);
}
