// Tap offsets against an independent long-double evaluation, exact symmetries
// of the pattern, pass-name sanitising and the gather header's verdicts.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <utility>
#include <stdexcept>
#include <string>

#include "spiral/codegen.hpp"

using spiral::codegen::macro_prefix;
using spiral::codegen::spiral_taps;

namespace {

std::uint32_t bits(float value) {
    std::uint32_t out;
    std::memcpy(&out, &value, sizeof out);
    return out;
}

// The definition, evaluated naively: 2*pi*tau*alpha in long double with no
// reduction at all. Its 64-bit mantissa keeps the angle's error below 1e-9
// even for tau near 1e9, far under float resolution.
struct OracleTap {
    long double alpha, x, y;
};
OracleTap oracle_tap(int n, long long tau, int i) {
    const long double pi = 3.141592653589793238462643383279502884L;
    const long double alpha = (i + 0.5L) / n;
    const long double angle = 2 * pi * static_cast<long double>(tau) * alpha;
    return {alpha, alpha * std::cos(angle), alpha * std::sin(angle)};
}

// Within one float ulp at the scale of alpha (|x|, |y| <= alpha): the
// generator rounds a double to float, the oracle a long double, and the two
// may land on either side of a rounding boundary.
bool close_to(float value, long double exact, long double alpha) {
    return std::fabs(static_cast<long double>(value) - exact) <= alpha * 0x1p-23L;
}

}  // namespace

TEST_CASE("gather header: macro_prefix upper-cases and joins words with one underscore",
          "[codegen][gather]") {
    CHECK(macro_prefix("ao") == "AO");
    CHECK(macro_prefix("radiosity") == "RADIOSITY");
    CHECK(macro_prefix("deep radiosity") == "DEEP_RADIOSITY");
    CHECK(macro_prefix("  SSAO-v2  ") == "SSAO_V2");
    CHECK(macro_prefix("a__b") == "A_B");
    CHECK(macro_prefix("_x") == "X");
    CHECK(macro_prefix("pass 2") == "PASS_2");
}

TEST_CASE("gather header: macro_prefix refuses names that cannot become a macro prefix",
          "[codegen][gather]") {
    CHECK_THROWS_AS(macro_prefix(""), std::invalid_argument);
    CHECK_THROWS_AS(macro_prefix("3d"), std::invalid_argument);
    CHECK_THROWS_AS(macro_prefix("!!"), std::invalid_argument);
    CHECK_THROWS_AS(macro_prefix("gl_foo"), std::invalid_argument);
    CHECK_THROWS_AS(macro_prefix("GL foo"), std::invalid_argument);
    CHECK_THROWS_AS(macro_prefix("a\nb"), std::invalid_argument);
    CHECK_THROWS_AS(macro_prefix("caf\xc3\xa9"), std::invalid_argument);
    CHECK_THROWS_AS(macro_prefix(std::string(65, 'a')), std::invalid_argument);
    CHECK(macro_prefix(std::string(64, 'a')) == std::string(64, 'A'));
    CHECK(macro_prefix("glow") == "GLOW");  // only the GL_ prefix is reserved
}

TEST_CASE("gather header: shell_quote quotes only when needed", "[codegen]") {
    using spiral::codegen::shell_quote;
    CHECK(shell_quote("ao") == "ao");
    CHECK(shell_quote("deep radiosity") == "'deep radiosity'");
    CHECK(shell_quote("it's") == "'it'\\''s'");
    CHECK(shell_quote("") == "''");
    CHECK(shell_quote("a\\") == "'a\\'");
}

TEST_CASE("gather header: hand-derived taps are exact", "[codegen][gather]") {
    // n = 2, tau = 1: alpha = 1/4, 3/4 at 1/4 and 3/4 of a turn, so the
    // offsets are (0, 1/4) and (0, -3/4); the cosines must be exactly 0.
    auto two = spiral_taps(2, 1);
    REQUIRE(two.size() == 2);
    CHECK(bits(two[0].x) == bits(0.0f));
    CHECK(two[0].y == 0.25f);
    CHECK(bits(two[1].x) == bits(0.0f));
    CHECK(two[1].y == -0.75f);
    CHECK(two[0].alpha == 0.25f);
    CHECK(two[1].alpha == 0.75f);

    // n = 4, tau = 1: alpha_i = 1/8, 3/8, 5/8, 7/8 at 1/8, 3/8, 5/8, 7/8 turn, i.e.
    // 45, 135, 225, 315 degrees: (+-alpha/sqrt 2, +-alpha/sqrt 2).
    auto four = spiral_taps(4, 1);
    const double h = std::sqrt(0.5);
    CHECK(four[0].x == static_cast<float>(h / 8));
    CHECK(four[0].y == static_cast<float>(h / 8));
    CHECK(four[1].x == static_cast<float>(-3 * h / 8));
    CHECK(four[1].y == static_cast<float>(3 * h / 8));
    CHECK(four[2].x == static_cast<float>(-5 * h / 8));
    CHECK(four[2].y == static_cast<float>(-5 * h / 8));
    CHECK(four[3].x == static_cast<float>(7 * h / 8));
    CHECK(four[3].y == static_cast<float>(-7 * h / 8));
}

TEST_CASE("gather header: taps match the long-double oracle for every n <= 300",
          "[codegen][gather]") {
    int compared = 0;
    for (int n = 1; n <= 300; ++n) {
        for (long long tau :
             {1LL, 2LL, n / 2 + 1LL, n - 1LL, 1LL * n, n + 1LL, 7LL * n + 3, 999'999'937LL}) {
            if (tau < 1) continue;
            const auto taps = spiral_taps(n, static_cast<int>(tau));
            REQUIRE(taps.size() == static_cast<std::size_t>(n));
            for (int i = 0; i < n; ++i) {
                const OracleTap exact = oracle_tap(n, tau, i);
                const auto& tap = taps[static_cast<std::size_t>(i)];
                INFO("n = " << n << ", tau = " << tau << ", i = " << i);
                REQUIRE(tap.alpha == static_cast<float>(exact.alpha));
                REQUIRE(close_to(tap.x, exact.x, exact.alpha));
                REQUIRE(close_to(tap.y, exact.y, exact.alpha));
                ++compared;
            }
        }
    }
    CHECK(compared > 300000);
}

TEST_CASE("gather header: fractional turns match the long-double oracle",
          "[codegen][gather][fractional]") {
    // tau = p / m: the oracle takes the angle 2*pi*(p/m)*alpha in long double.
    const long double pi = 3.141592653589793238462643383279502884L;
    for (int n = 1; n <= 64; ++n)
        for (long long m : {2LL, 3LL, 8LL})
            for (long long p : {1LL, 3LL, 49LL, m * n - 1, m * n + 5}) {
                if (p < 1) continue;
                const auto taps = spiral_taps(n, p, m);
                REQUIRE(taps.size() == static_cast<std::size_t>(n));
                for (int i = 0; i < n; ++i) {
                    const long double alpha = (i + 0.5L) / n;
                    const long double angle =
                        2 * pi * static_cast<long double>(p) / static_cast<long double>(m) * alpha;
                    const auto& tap = taps[static_cast<std::size_t>(i)];
                    INFO("n = " << n << ", p = " << p << ", m = " << m << ", i = " << i);
                    REQUIRE(close_to(tap.x, alpha * std::cos(angle), alpha));
                    REQUIRE(close_to(tap.y, alpha * std::sin(angle), alpha));
                }
            }
    // m = 1 and the same turns written as 4p / 4 give the same bits.
    for (int n = 1; n <= 64; ++n)
        for (int tau = 1; tau <= n; ++tau) {
            const auto a = spiral_taps(n, tau), b = spiral_taps(n, 4 * tau, 4);
            for (int i = 0; i < n; ++i) {
                CHECK(bits(a[static_cast<std::size_t>(i)].x) ==
                      bits(b[static_cast<std::size_t>(i)].x));
                CHECK(bits(a[static_cast<std::size_t>(i)].y) ==
                      bits(b[static_cast<std::size_t>(i)].y));
            }
        }
    CHECK_THROWS_AS(spiral_taps(4, 1, 0), std::invalid_argument);
}

TEST_CASE("gather header: the gather header for fractional turns states p/m and its discrepancy",
          "[codegen][gather][fractional]") {
    const std::string text =
        spiral::codegen::make_gather_header("ao", 16, std::nullopt, {"test"}, 8);
    // n = 16, m = 8: tau = 49/8, K = 1420 of 8192 (the brute force confirms
    // this in the optimizer tests).
    CHECK(text.find("#define AO_NUM_SPIRAL_TURNS 6.125\n") != std::string::npos);
    CHECK(text.find("#define AO_SPIRAL_TURNS_NUMERATOR 49\n") != std::string::npos);
    CHECK(text.find("#define AO_SPIRAL_TURNS_DENOMINATOR 8\n") != std::string::npos);
    CHECK(text.find("D(16, 49/8) = 1420/8192") != std::string::npos);
    const std::string by_hand =
        spiral::codegen::make_gather_header("ao", 16, 56, {"test"}, 8);  // 56/8 = 7 turns
    CHECK(by_hand.find("tau = 56/8 (set by hand; NOT the optimum)") != std::string::npos);
    // 7 turns: D(16, 7) = 192/1024, i.e. 1536 in units of 1/8192.
    CHECK(by_hand.find("D(16, 56/8) = 1536/8192") != std::string::npos);
}

TEST_CASE("gather header: the exact angle reduction gives exact symmetries", "[codegen][gather]") {
    for (int n : {1, 2, 3, 7, 11, 19, 64, 255, 1000}) {
        for (int tau : {1, 2, 3, n / 3 + 1, n}) {
            const auto base = spiral_taps(n, tau);
            // tau + 2n is the same pattern; tau + n turns every tap by half a
            // turn ((2i+1) n / 2n is an odd number of half turns); 4n - tau
            // mirrors it in the x axis.
            const auto same = spiral_taps(n, tau + 2 * n);
            const auto half_turn = spiral_taps(n, tau + n);
            const auto mirrored = spiral_taps(n, 4 * n - tau);
            for (std::size_t i = 0; i < base.size(); ++i) {
                INFO("n = " << n << ", tau = " << tau << ", i = " << i);
                CHECK(bits(same[i].x) == bits(base[i].x));
                CHECK(bits(same[i].y) == bits(base[i].y));
                CHECK(bits(half_turn[i].x) == bits(base[i].x == 0 ? 0.0f : -base[i].x));
                CHECK(bits(half_turn[i].y) == bits(base[i].y == 0 ? 0.0f : -base[i].y));
                CHECK(bits(mirrored[i].x) == bits(base[i].x));
                CHECK(bits(mirrored[i].y) == bits(base[i].y == 0 ? 0.0f : -base[i].y));
            }
        }
    }
}

TEST_CASE("gather header: spiral_taps refuses n < 1 and tau < 1", "[codegen][gather]") {
    CHECK_THROWS_AS(spiral_taps(0, 1), std::invalid_argument);
    CHECK_THROWS_AS(spiral_taps(3, 0), std::invalid_argument);
    CHECK_THROWS_AS(spiral_taps(3, -2), std::invalid_argument);
}

namespace {

spiral::codegen::GatherSpec spec(int n, int tau, std::vector<int> ties, std::int64_t optimum_k,
                                 int chosen_tau, std::int64_t chosen_k) {
    spiral::codegen::GatherSpec s;
    s.pass = "ao";
    s.optimum.n = n;
    s.optimum.tau = tau;
    s.optimum.ties = std::move(ties);
    s.optimum.scaled = optimum_k;
    s.chosen.n = n;
    s.chosen.tau = chosen_tau;
    s.chosen.scaled = chosen_k;
    return s;
}

const spiral::codegen::Provenance kProvenance{"test"};

}  // namespace

TEST_CASE("gather header: the gather header states whether tau is the optimum",
          "[codegen][gather]") {
    using spiral::codegen::format_gather_header;
    // K values are made up (n = 5, 4n^2 = 100): the header must report them as given.
    SECTION("the optimum itself") {
        const auto text = format_gather_header(spec(5, 2, {2, 3}, 44, 2, 44), kProvenance);
        CHECK(text.find("tau = 2 (the optimum)") != std::string::npos);
        CHECK(text.find("D(5, 2) = 44/100 = 0.44: the minimum over tau in [1, 5], reached by "
                        "tau = 2, 3.") != std::string::npos);
        CHECK(text.find("#define AO_NUM_SPIRAL_TURNS 2\n") != std::string::npos);
        CHECK(text.find("NOT") == std::string::npos);
    }
    SECTION("a tie set by hand") {
        const auto text = format_gather_header(spec(5, 2, {2, 3}, 44, 3, 44), kProvenance);
        CHECK(text.find("tau = 3 (set by hand; ties with the optimum)") != std::string::npos);
        CHECK(text.find("#define AO_NUM_SPIRAL_TURNS 3\n") != std::string::npos);
        CHECK(text.find("NOT") == std::string::npos);
    }
    SECTION("a worse tau set by hand") {
        const auto text = format_gather_header(spec(5, 2, {2, 3}, 44, 5, 80), kProvenance);
        CHECK(text.find("tau = 5 (set by hand; NOT the optimum)") != std::string::npos);
        CHECK(text.find("worse by\n// 36/100 = 0.36:\n"
                        "//   chosen:  D(5, 5) = 80/100 = 0.8\n"
                        "//   optimum: D(5, 2) = 44/100 = 0.44 (tau = 2, 3)\n") !=
              std::string::npos);
        CHECK(text.find("#define AO_NUM_SPIRAL_TURNS 5\n") != std::string::npos);
    }
    SECTION("inconsistent specs are refused") {
        CHECK_THROWS_AS(format_gather_header(spec(5, 2, {2, 3}, 44, 4, 40), kProvenance),
                        std::invalid_argument);  // below the optimum
        CHECK_THROWS_AS(format_gather_header(spec(5, 2, {2, 3}, 44, 3, 50), kProvenance),
                        std::invalid_argument);  // a tie with a different K
        auto wrong_n = spec(5, 2, {2, 3}, 44, 2, 44);
        wrong_n.chosen.n = 6;
        CHECK_THROWS_AS(format_gather_header(wrong_n, kProvenance), std::invalid_argument);
        auto bad_name = spec(5, 2, {2, 3}, 44, 2, 44);
        bad_name.pass = "9lives";
        CHECK_THROWS_AS(format_gather_header(bad_name, kProvenance), std::invalid_argument);
    }
}

TEST_CASE("gather header: every printed offset and alpha reads back as the same float",
          "[codegen][gather]") {
    // 255 taps with an awkward tau, and 1000 taps where tiny offsets print
    // with an exponent: parse each "vec2(x, y),  // i" and "a,  // i" line.
    for (auto [n, tau] : {std::pair{255, 97}, std::pair{1000, 501}}) {
        auto s = spec(n, tau, {tau}, 4, tau, 4);
        const auto text = spiral::codegen::format_gather_header(s, kProvenance);
        const auto taps = spiral_taps(n, tau);
        std::size_t offsets = text.find("vec2[](\n"), alphas = text.find("float[](\n");
        REQUIRE(offsets != std::string::npos);
        REQUIRE(alphas != std::string::npos);
        for (int i = 0; i < n; ++i) {
            INFO("n = " << n << ", i = " << i);
            offsets = text.find("    vec2(", offsets) + 9;
            char* end = nullptr;
            const float x = std::strtof(text.c_str() + offsets, &end);
            REQUIRE(std::strncmp(end, ", ", 2) == 0);
            const float y = std::strtof(end + 2, &end);
            REQUIRE(*end == ')');
            CHECK(bits(x) == bits(taps[static_cast<std::size_t>(i)].x));
            CHECK(bits(y) == bits(taps[static_cast<std::size_t>(i)].y));
            alphas = text.find("\n    ", alphas) + 5;
            CHECK(std::strtof(text.c_str() + alphas, nullptr) ==
                  taps[static_cast<std::size_t>(i)].alpha);
        }
    }
}

TEST_CASE("gather header: make_gather_header uses the optimizer's optimum and K",
          "[codegen][gather]") {
    const auto optimum = spiral::search(11);
    const auto text = spiral::codegen::make_gather_header("ao", 11, std::nullopt, kProvenance);
    CHECK(text.find("#define AO_NUM_TAPS 11\n") != std::string::npos);
    CHECK(text.find("#define AO_NUM_SPIRAL_TURNS " + std::to_string(optimum.tau) + "\n") !=
          std::string::npos);
    CHECK(text.find("D(11, " + std::to_string(optimum.tau) +
                    ") = " + std::to_string(optimum.scaled) + "/484") != std::string::npos);

    // tau = n puts every tap on one ray: never optimal for n = 11.
    const auto ray = spiral::discrepancy(11, 11);
    REQUIRE(ray.scaled > optimum.scaled);
    const auto forced = spiral::codegen::make_gather_header("ao", 11, 11, kProvenance);
    CHECK(forced.find("NOT the optimum") != std::string::npos);
    CHECK(forced.find("chosen:  D(11, 11) = " + std::to_string(ray.scaled) + "/484") !=
          std::string::npos);
    CHECK(forced.find("worse by\n// " + std::to_string(ray.scaled - optimum.scaled) + "/484") !=
          std::string::npos);

    // tau beyond n is kept as given; tau + 2n has the optimum's discrepancy.
    const auto wrapped =
        spiral::codegen::make_gather_header("ao", 11, optimum.tau + 22, kProvenance);
    CHECK(wrapped.find("#define AO_NUM_SPIRAL_TURNS " + std::to_string(optimum.tau + 22) + "\n") !=
          std::string::npos);
    CHECK(wrapped.find("ties with the optimum") != std::string::npos);

    CHECK_THROWS_AS(spiral::codegen::make_gather_header("ao", 0, std::nullopt, kProvenance),
                    std::invalid_argument);
    CHECK_THROWS_AS(spiral::codegen::make_gather_header("ao", 11, 0, kProvenance),
                    std::invalid_argument);
}
