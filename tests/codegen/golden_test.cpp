// Golden files: spiralgen must reproduce them byte for byte, and their numbers
// must equal values derived by hand below (closed forms evaluated here, not by
// the generator), so a golden file cannot silently enshrine a wrong value.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "process.hpp"

namespace {

const std::string kSpiralgen = SPIRALGEN_PATH;
const std::string kGoldenDir = CODEGEN_GOLDEN_DIR;

spiral::test::ProcessResult spiralgen(const std::string& arguments) {
    return spiral::test::run_command("'" + kSpiralgen + "' " + arguments);
}

std::string golden(const std::string& name) {
    const std::string text = spiral::test::read_file(kGoldenDir + "/" + name);
    REQUIRE_FALSE(text.empty());
    return text;
}

// The float literals inside the initializer of `symbol`, in order.
std::vector<float> array_values(const std::string& text, const std::string& symbol) {
    // The declaration, not a mention in the comments: a line "const <type> SYMBOL[".
    auto start = text.find(symbol + "[");
    while (start != std::string::npos &&
           text.compare(text.rfind('\n', start) + 1, 6, "const ") != 0)
        start = text.find(symbol + "[", start + 1);
    REQUIRE(start != std::string::npos);
    const auto open = text.find("](", start);
    const auto close = text.find("\n);", open);
    REQUIRE(close != std::string::npos);
    std::vector<float> values;
    for (std::size_t line = text.find('\n', open) + 1; line < close;
         line = text.find('\n', line) + 1) {
        // One element a line; the "// i" index comment is not a value.
        std::string element = text.substr(line, text.find("  //", line) - line);
        for (auto at = element.find("vec2"); at != std::string::npos; at = element.find("vec2"))
            element.erase(at, 4);
        for (char& c : element)
            if (c == '(' || c == ')' || c == ',') c = ' ';
        const char* cursor = element.c_str();
        for (;;) {
            while (*cursor == ' ') ++cursor;
            if (*cursor == '\0') break;
            char* end = nullptr;
            values.push_back(std::strtof(cursor, &end));
            REQUIRE(end != cursor);
            cursor = end;
        }
    }
    return values;
}

void check_matches_generator(const std::string& golden_name, const std::string& arguments) {
    const auto result = spiralgen(arguments);
    REQUIRE(result.status == 0);
    CHECK(result.err.empty());
    CHECK(result.out == golden(golden_name));
}

}  // namespace

TEST_CASE("golden: ao, 1 tap", "[codegen][golden]") {
    // n = 1: the only tau is 1. alpha_0 = 1/2 at 2*pi*1*(1/2) = pi, so the
    // offset is (-1/2, 0). D: in half units the domain is [0,2] x [0,2) and
    // 4n^2 = 4; a closed sector of zero area around the tap has
    // |4n*1 - 0| = 4, the largest possible, so K = 4 and D = 1.
    check_matches_generator("ao_taps_1.glsl", "header --pass ao --taps 1");
    const std::string text = golden("ao_taps_1.glsl");
    CHECK(array_values(text, "AO_TAP_OFFSETS") == std::vector<float>{-0.5f, 0.0f});
    CHECK(array_values(text, "AO_TAP_ALPHAS") == std::vector<float>{0.5f});
    CHECK(text.find("#define AO_NUM_TAPS 1\n#define AO_NUM_SPIRAL_TURNS 1\n") != std::string::npos);
    CHECK(text.find("D(1, 1) = 4/4 = 1") != std::string::npos);
}

TEST_CASE("golden: ao, 3 taps", "[codegen][golden]") {
    // n = 3: tau = 3 puts all taps on one ray, and D(3,1) = D(3,2) by mirror
    // symmetry, so the optimum is tau = 1 with ties {1, 2}.
    // alpha = 1/6, 1/2, 5/6 at angles 2*pi*alpha = pi/3, pi, 5pi/3:
    //   (1/6)(cos, sin)(pi/3)  = (1/12, sqrt3/12)
    //   (1/2)(cos, sin)(pi)    = (-1/2, 0)
    //   (5/6)(cos, sin)(5pi/3) = (5/12, -5 sqrt3/12)
    // K: half units, domain [0,6] x [0,6), taps at (1,1), (3,3), (5,5),
    // 4n^2 = 36, local*36 = |12*count - W*L|. The open sector x in (1,5)
    // (W = 4) over the whole circle except angle 3 (L = 6) holds no tap:
    // |0 - 24| = 24. Nothing does worse: a closed sector needs W*L >= 0 with
    // count <= 3 and two or three taps force W, L >= 2 (|24-4|, |36-16| = 20);
    // an empty open sector avoids x = 3 or y = 3, capping W*L at 4*6 = 24.
    // So K = 24, D = 24/36.
    check_matches_generator("ao_taps_3.glsl", "header --pass ao --taps 3");
    const std::string text = golden("ao_taps_3.glsl");
    const double s3 = std::sqrt(3.0);
    CHECK(array_values(text, "AO_TAP_OFFSETS") ==
          std::vector<float>{static_cast<float>(1.0 / 12), static_cast<float>(s3 / 12), -0.5f, 0.0f,
                             static_cast<float>(5.0 / 12), static_cast<float>(-5 * s3 / 12)});
    CHECK(array_values(text, "AO_TAP_ALPHAS") ==
          std::vector<float>{static_cast<float>(1.0 / 6), 0.5f, static_cast<float>(5.0 / 6)});
    CHECK(text.find("#define AO_NUM_SPIRAL_TURNS 1\n") != std::string::npos);
    CHECK(text.find("D(3, 1) = 24/36 = 0.6666666666666666: the minimum over tau in [1, 3], "
                    "reached by tau = 1, 2.") != std::string::npos);
}

TEST_CASE("golden: 'deep radiosity', 2 taps, tau 2 set by hand", "[codegen][golden]") {
    // alpha = 1/4, 3/4 at 2*pi*2*alpha = pi and 3pi (= pi): both taps on the
    // negative x axis, (-1/4, 0) and (-3/4, 0).
    // K, half units: domain [0,4] x [0,4), 4n^2 = 16, local*16 = |8*count - W*L|.
    //   tau = 2: taps (1,2), (3,2). A closed zero-area sector x in [0,4] at
    //     angle 2 holds both: |16 - 0| = 16, the maximum. K = 16, D = 1.
    //   tau = 1: taps (1,1), (3,3). Both taps need W >= 2 and L >= 2:
    //     |16 - 4| = 12; one tap at most |8 - 0| = 8 or |8 - 16| = 8; an
    //     empty open sector has W*L <= 8. K = 12, D = 3/4; tau = 1 is the optimum.
    // So the header must say: worse by 4/16 = 0.25.
    check_matches_generator("deep_radiosity_taps_2_tau_2.glsl",
                            "header --pass 'deep radiosity' --taps 2 --tau 2");
    const std::string text = golden("deep_radiosity_taps_2_tau_2.glsl");
    CHECK(array_values(text, "DEEP_RADIOSITY_TAP_OFFSETS") ==
          std::vector<float>{-0.25f, 0.0f, -0.75f, 0.0f});
    CHECK(array_values(text, "DEEP_RADIOSITY_TAP_ALPHAS") == std::vector<float>{0.25f, 0.75f});
    CHECK(text.find("#define DEEP_RADIOSITY_NUM_SPIRAL_TURNS 2\n") != std::string::npos);
    CHECK(text.find("NOT the optimum. Its discrepancy is worse by\n// 4/16 = 0.25:\n"
                    "//   chosen:  D(2, 2) = 16/16 = 1\n"
                    "//   optimum: D(2, 1) = 12/16 = 0.75 (tau = 1)\n") != std::string::npos);
    CHECK(text.find("// Command: `spiralgen header --pass 'deep radiosity' --taps 2 --tau 2`\n") !=
          std::string::npos);
}

TEST_CASE("golden: blur, radius 1", "[codegen][golden]") {
    // Default sigma = 1/2: weights proportional to e^-2, 1, e^-2 (k^2 / (2 sigma^2)
    // = 2 at k = +-1), so w0 = 1/(1 + 2e^-2) = 0.78698..., w1 = e^-2/(1 + 2e^-2) = 0.10650...
    check_matches_generator("blur_radius_1.glsl", "blur --radius 1");
    const std::string text = golden("blur_radius_1.glsl");
    const double e2 = std::exp(-2.0);
    const float w0 = static_cast<float>(1 / (1 + 2 * e2));
    const float w1 = static_cast<float>(e2 / (1 + 2 * e2));
    CHECK(array_values(text, "BLUR_WEIGHTS") == std::vector<float>{w1, w0, w1});
    CHECK(text.find("#define BLUR_RADIUS 1\n#define BLUR_SIGMA 0.5\n") != std::string::npos);
}
