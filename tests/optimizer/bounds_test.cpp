// The lower bounds the search prunes with, checked against the exact K of
// every candidate: single-band probes (evaluate_band) and eight-band probes
// (evaluate_bands, which must equal them), the early-stopped sweep
// with and without a known lower bound, and the eight-lane sweep against the
// one-band-at-a-time sweep. The exact K comes from discrepancy(), whose sweep
// reports a worst sector and so never takes the lane path; the brute force
// checks both on small n. White box: these are the internal functions the
// search calls (optimizer/src/evaluate.hpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "evaluate.hpp"
#include "spiral/optimizer.hpp"

namespace {

constexpr std::int64_t kNoBound = std::numeric_limits<std::int64_t>::max();

// Every check for one candidate; returns an empty string or what failed.
// all_bands: probe every band (and require their maximum to be K), else
// the search's grid of 5% steps and the two ends.
std::string check_candidate(int n, std::int64_t p, std::int64_t m, bool all_bands) {
    const std::int64_t exact = spiral::discrepancy(n, p, m).scaled;
    const std::int64_t cluster = spiral::discrepancy_lower_bound(n, p, m);
    auto where = [&] {
        return "n = " + std::to_string(n) + ", p = " + std::to_string(p) +
               ", m = " + std::to_string(m) + ", K = " + std::to_string(exact) + ": ";
    };
    if (cluster > exact) return where() + "cluster bound " + std::to_string(cluster);

    spiral::detail::BandScratch scratch;
    std::vector<std::int64_t> bands;
    if (all_bands) {
        for (std::int64_t k = 1; k <= n; ++k) bands.push_back(k);
    } else {
        for (int percent = 5; percent <= 95; percent += 5)
            bands.push_back(std::max<std::int64_t>(1, percent * std::int64_t{n} / 100));
        bands.push_back(1);
        bands.push_back(n);
    }
    std::int64_t largest = 0;
    for (const std::int64_t k : bands) {
        const std::int64_t probe = spiral::detail::evaluate_band(n, p, m, k, scratch);
        if (probe > exact)
            return where() + "band " + std::to_string(k) + " gives " + std::to_string(probe);
        largest = std::max(largest, probe);
    }
    // Eight bands at once (vector lanes over one sorted pass) must give each
    // band's own value, for any grouping.
    for (std::size_t g = 0; g < bands.size(); g += 8) {
        const int count = static_cast<int>(std::min<std::size_t>(8, bands.size() - g));
        std::int64_t excess[8];
        spiral::detail::evaluate_bands(n, p, m, bands.data() + g, count, scratch, excess);
        for (int j = 0; j < count; ++j)
            if (excess[j] != spiral::detail::evaluate_band(n, p, m, bands[g + j], scratch))
                return where() + "eight-band probe of band " + std::to_string(bands[g + j]) +
                       " gives " + std::to_string(excess[j]);
    }
    // The empty open band (the whole circle, nothing inside) is the one
    // sector no probe covers; K is the larger of it and every band.
    const std::int64_t empty = (n >= 2 ? 2 : 1) * 2 * std::int64_t{n} * m;
    if (all_bands && std::max(largest, empty) != exact)
        return where() + "largest band " + std::to_string(largest);

    // Early-stopped sweeps: below K they must stop above the bound and at most
    // K, and name a band that exceeds it; at K they must return K exactly.
    for (const bool lanes : {true, false}) {
        for (const std::int64_t bound : {exact - 1, exact, cluster, exact / 2, kNoBound}) {
            for (const std::int64_t known : {std::int64_t{0}, cluster}) {
                std::int64_t band = -1;
                const std::int64_t value =
                    spiral::detail::evaluate(n, p, m, bound, nullptr, &band, known, lanes);
                const std::string run = "bound " + std::to_string(bound) + ", known " +
                                        std::to_string(known) + (lanes ? ", lanes" : ", scalar") +
                                        ": ";
                if (exact <= bound) {
                    if (value != exact || band != 0)
                        return where() + run + "returned " + std::to_string(value);
                    continue;
                }
                if (value <= bound || value > exact)
                    return where() + run + "stopped at " + std::to_string(value);
                if (band < 0 || band > n) return where() + run + "band " + std::to_string(band);
                if (band > 0 && spiral::detail::evaluate_band(n, p, m, band, scratch) <= bound)
                    return where() + run + "named band " + std::to_string(band) +
                           " that does not exceed the bound";
            }
            if (!lanes) break;  // the scalar sweep once, at the first bound (K - 1)
        }
    }
    return {};
}

}  // namespace

TEST_CASE("bounds: probes and early-stopped sweeps never exceed K, every tau and n <= 200",
          "[bounds][property]") {
    for (int n = 1; n <= 200; ++n)
        for (int tau = 1; tau <= n; ++tau) {
            const std::string failure = check_candidate(n, tau, 1, n <= 64);
            if (!failure.empty()) FAIL(failure);
        }
    SUCCEED();
}

TEST_CASE("bounds: probes and early-stopped sweeps never exceed K for fractional turns",
          "[bounds][fractional][property]") {
    // m = 32 has more angle slots than 16 n: the probes sort instead of
    // bucketing.
    for (const std::int64_t m : {2, 4, 8, 32})
        for (int n = 1; n <= (m == 32 ? 16 : 40); ++n)
            for (std::int64_t p = 1; p <= n * m; ++p) {
                const std::string failure = check_candidate(n, p, m, true);
                if (!failure.empty()) FAIL(failure);
            }
    SUCCEED();
}

TEST_CASE("bounds: the lane sweep and every probe agree with the brute force on small n",
          "[bounds][oracle]") {
    spiral::detail::BandScratch scratch;
    auto check = [&](int n, std::int64_t p, std::int64_t m) {
        INFO("n = " << n << ", p = " << p << ", m = " << m);
        const std::int64_t truth = spiral::discrepancy_brute_force(n, p, m).scaled;
        CHECK(spiral::detail::evaluate(n, p, m, kNoBound, nullptr) == truth);
        CHECK(spiral::discrepancy_lower_bound(n, p, m) <= truth);
        for (std::int64_t k = 1; k <= n; ++k)
            CHECK(spiral::detail::evaluate_band(n, p, m, k, scratch) <= truth);
    };
    for (int n = 1; n <= 14; ++n)
        for (std::int64_t tau = 1; tau <= n; ++tau) check(n, tau, 1);
    for (const std::int64_t m : {2, 4})
        for (int n = 1; n <= 7; ++n)
            for (std::int64_t p = 1; p <= n * m; ++p) check(n, p, m);
}

TEST_CASE("bounds: the lane sweep is exact at the edge of its 32-bit range", "[bounds][hard]") {
    // 4 n^2 m = 2^28 is the largest product the lanes take: keys reach 2^28
    // and differences 2^29 there. One pattern with well-spread taps, one where
    // taps share angles (gcd(p, n) > 1), at m = 1 and m = 4.
    struct Case {
        int n;
        std::int64_t p, m;
    };
    for (const Case c : {Case{8192, 2531, 1}, Case{8192, 3072, 1}, Case{4096, 6327, 4}}) {
        INFO("n = " << c.n << ", p = " << c.p << ", m = " << c.m);
        REQUIRE(4 * std::int64_t{c.n} * c.n * c.m == std::int64_t{1} << 28);
        const std::int64_t lanes = spiral::detail::evaluate(c.n, c.p, c.m, kNoBound, nullptr);
        const std::int64_t scalar =
            spiral::detail::evaluate(c.n, c.p, c.m, kNoBound, nullptr, nullptr, 0, false);
        CHECK(lanes == scalar);
        CHECK(lanes == spiral::discrepancy(c.n, c.p, c.m).scaled);
    }
}
