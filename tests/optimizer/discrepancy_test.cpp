// D(n, tau): the fast evaluator against the brute-force oracle, hand-derived
// small cases, invariances, and hard cases.
//
// Units: coordinates in 1/(2n), so D = K / (4n^2) with
// K = |4n * count - width * arc| for the worst sector (docs/design.md, section 3).
#include <catch2/catch.hpp>

#include <cstdint>
#include <numeric>
#include <stdexcept>

#include "spiral/optimizer.hpp"
#include "tap_oracle.hpp"

using spiral::discrepancy;
using spiral::discrepancy_brute_force;
using spiral::test::recounted_excess;

namespace {

void check_against_oracle(int n, int tau) {
    INFO("n = " << n << ", tau = " << tau);
    const auto fast = discrepancy(n, tau);
    const auto oracle = discrepancy_brute_force(n, tau);
    REQUIRE(fast.scaled == oracle.scaled);
    // Both reported sectors must really attain K when their taps are recounted.
    CHECK(recounted_excess(n, tau, fast.worst) == fast.scaled);
    CHECK(recounted_excess(n, tau, oracle.worst) == oracle.scaled);
}

}  // namespace

TEST_CASE("discrepancy: fast evaluator equals the brute force for every tau and n <= 40",
          "[discrepancy][oracle]") {
    const int n = GENERATE(range(1, 41));
    for (int tau = 1; tau <= n; ++tau) check_against_oracle(n, tau);
}

TEST_CASE("discrepancy: fast evaluator equals the brute force on sampled larger n",
          "[discrepancy][oracle]") {
    // Primes, powers of two, Fibonacci numbers and highly composite n, each
    // with a near-optimal tau, a poor one and a shared-angle one where possible.
    const auto [n, tau] = GENERATE(table<int, int>({
        {41, 16},
        {41, 3},
        {55, 21},
        {55, 34},
        {64, 17},
        {64, 32},
        {64, 24},
        {89, 34},
        {97, 41},
        {100, 38},
        {100, 50},
        {120, 45},
        {127, 1},
        {144, 55},
        {160, 61},
        {160, 40},
    }));
    check_against_oracle(n, tau);
}

TEST_CASE("discrepancy: hand-derived small cases", "[discrepancy][exact]") {
    SECTION("n = 1: the lone tap is a closed sector of zero area holding every tap") {
        // Tap at alpha = 1/2, angle 1/2 turn. The degenerate closed sector
        // through it has count/n = 1 and area 0, so local = 1, and local can
        // never exceed 1 (both count/n and the area lie in [0, 1]): D = 1,
        // K = 4n^2 = 4, for every tau.
        for (int tau = 1; tau <= 3; ++tau) {
            CHECK(discrepancy(1, tau).scaled == 4);
            CHECK(discrepancy(1, tau).value() == 1.0);
        }
    }
    SECTION("n = 2, tau = 1: both taps in one quarter of the weighted area") {
        // Taps at (alpha, angle) = (1/4, 1/4) and (3/4, 3/4).
        // Closed [1/4, 3/4] x [1/4, 3/4]: count 2/2 = 1, area 1/2 * 1/2 = 1/4,
        // local = 3/4. Upper bound: a closed sector holding both taps spans
        // alpha 1/2 and half a turn (area >= 1/4); holding one gives <= 1/2.
        // An open sector is empty only if it avoids both taps: a band holding
        // both radii leaves an arc of at most 1/2 (area <= 1/2), a band with
        // one radius has width <= 3/4 (area < 3/4), none has width <= 1/2;
        // holding a tap costs 1/2. So D = 3/4, K = 3/4 * 16 = 12.
        const auto d = discrepancy(2, 1);
        CHECK(d.scaled == 12);
        CHECK(d.denominator() == 16);
    }
    SECTION("n = 3, tau = 1: an open sector around the middle tap's radius") {
        // Taps on the diagonal: (1/6, 1/6), (1/2, 1/2), (5/6, 5/6).
        // The open band (1/6, 5/6) holds only the middle tap's radius; the
        // open arc "every angle except 1/2 turn" avoids it: count 0, area
        // 2/3 * 1 = 2/3. Upper bound: closed sectors with 2 or 3 taps need
        // width and arc >= 1/3 (2 taps: 2/3 - 1/9) or >= 2/3 (3 taps: 1 - 4/9),
        // so <= 5/9; one tap gives 1/3. Empty open sectors: a band with two or
        // three tap radii leaves arcs <= 2/3 with width <= 5/6 (<= 5/9), one
        // radius allows width <= 2/3 (<= 2/3), none width <= 1/3. Non-empty
        // open sectors give at most 1 - 1/3, and only the full band and circle
        // reach area 1, which holds two taps. So D = 2/3, K = 2/3 * 36 = 24.
        const auto d = discrepancy(3, 1);
        CHECK(d.scaled == 24);
        CHECK_FALSE(d.worst.closed);
        CHECK(recounted_excess(3, 1, d.worst) == 24);
    }
}

TEST_CASE("invariances: mirror and period", "[discrepancy][property]") {
    const int n = GENERATE(range(1, 61), 97, 128, 255, 1000);
    for (int tau = 1; tau <= n; tau += (n > 100 ? 37 : 1)) {
        INFO("n = " << n << ", tau = " << tau);
        const auto k = discrepancy(n, tau).scaled;
        CHECK(discrepancy(n, tau + n).scaled == k);
        if (tau < n) CHECK(discrepancy(n, n - tau).scaled == k);
        // The degenerate closed sector through one tap: D >= 1/n, K >= 4n.
        CHECK(k >= 4 * std::int64_t{n});
        CHECK(k <= 4 * std::int64_t{n} * n);
    }
}

TEST_CASE("discrepancy: hard cases", "[discrepancy][hard]") {
    SECTION("tau = n puts every tap on one ray: D = 1") {
        // The closed sector of zero arc along the ray holds all n taps.
        for (int n : {1, 2, 7, 64, 4096}) {
            INFO("n = " << n);
            CHECK(discrepancy(n, n).scaled == 4 * std::int64_t{n} * n);
        }
    }
    SECTION("tau = n/2 alternates between two opposite angles") {
        // Even i sit at angle 1/4 turn, odd i at 3/4. The closed band of all n
        // taps (width 2(n-1)) with the closed half circle from 1/4 to 3/4
        // (length n) holds all n: K = 4n*n - 2(n-1)*n = 2n^2 + 2n. A run of c
        // taps costs width 2(c-1) per half circle, so fewer taps score 2nc + 2n
        // at most; one angle alone scores 4n*ceil(c/2) with width >= 2(c-1);
        // open sectors avoiding both angles are at most a half circle of the
        // full band (2n * n). Checked against the brute force for n <= 40 above.
        for (int n : {2, 4, 10, 40, 4096}) {
            INFO("n = " << n);
            const std::int64_t big_n = n;
            CHECK(discrepancy(n, n / 2).scaled == 2 * big_n * big_n + 2 * big_n);
        }
    }
    SECTION("shared angles when gcd(tau, n) > 1 agree with the brute force") {
        for (const auto& [n, tau] :
             {std::pair{12, 4}, {12, 6}, {18, 6}, {30, 10}, {36, 9}, {48, 12}}) {
            REQUIRE(std::gcd(n, tau) > 1);
            check_against_oracle(n, tau);
        }
    }
    SECTION("large n: every product needs 64 bits") {
        // 4n^2 = 2.5e9 exceeds INT32_MAX for n = 25000; the closed forms above
        // must survive, and the worst sector must recount to K.
        constexpr int n = 25000;
        constexpr std::int64_t big_n = n;
        CHECK(discrepancy(n, n).scaled == 4 * big_n * big_n);
        CHECK(discrepancy(n, n / 2).scaled == 2 * big_n * big_n + 2 * big_n);
        for (int tau : {1597, 3}) {
            INFO("tau = " << tau);
            const auto d = discrepancy(4096, tau);
            CHECK(recounted_excess(4096, tau, d.worst) == d.scaled);
            CHECK(discrepancy(4096, 4096 - tau).scaled == d.scaled);
        }
    }
}

TEST_CASE("discrepancy: invalid arguments are rejected", "[discrepancy][errors]") {
    CHECK_THROWS_AS(discrepancy(0, 1), std::invalid_argument);
    CHECK_THROWS_AS(discrepancy(spiral::kMaxTaps + 1, 1), std::invalid_argument);
    CHECK_THROWS_AS(discrepancy(5, 0), std::invalid_argument);
    CHECK_THROWS_AS(discrepancy(5, -3), std::invalid_argument);
    CHECK_THROWS_AS(discrepancy_brute_force(0, 1), std::invalid_argument);
}
