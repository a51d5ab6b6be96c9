// format_table against tables written out by hand from results built by hand.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "spiral/codegen.hpp"

using spiral::SearchResult;
using spiral::codegen::format_table;
using spiral::codegen::parse_table_format;
using spiral::codegen::Provenance;
using spiral::codegen::TableFormat;

namespace {

SearchResult result(int n, int tau, std::vector<int> ties, std::int64_t scaled) {
    SearchResult r;
    r.n = n;
    r.tau = tau;
    r.ties = std::move(ties);
    r.scaled = scaled;
    return r;
}

// n = 2, 3 and 5 (4 missing, to exercise a gap). The K values need not be
// true optima here: the formatter must print whatever it is given.
// 24/36 has no short decimal form, so it tests the shortest round trip.
std::vector<SearchResult> sample() {
    return {result(2, 1, {1}, 12), result(3, 1, {1, 2}, 24), result(5, 2, {2, 3}, 44)};
}

const Provenance kProvenance{"spiralgen table --min-n 2 --max-n 5 --format X"};

}  // namespace

TEST_CASE("table format: parse_table_format accepts exactly the five names", "[codegen][table]") {
    CHECK(parse_table_format("cpp") == TableFormat::cpp);
    CHECK(parse_table_format("glsl") == TableFormat::glsl);
    CHECK(parse_table_format("json") == TableFormat::json);
    CHECK(parse_table_format("csv") == TableFormat::csv);
    CHECK(parse_table_format("md") == TableFormat::md);
    CHECK_FALSE(parse_table_format("CPP"));
    CHECK_FALSE(parse_table_format(""));
    CHECK_FALSE(parse_table_format("markdown"));
    CHECK_FALSE(parse_table_format("json "));
    for (auto format : {TableFormat::cpp, TableFormat::glsl, TableFormat::json, TableFormat::csv,
                        TableFormat::md})
        CHECK(parse_table_format(spiral::codegen::to_string(format)) == format);
}

TEST_CASE("table format: json is one object per result with the exact fraction",
          "[codegen][table]") {
    const std::string expected =
        "[\n"
        "  "
        "{\"n\":2,\"tau\":1,\"p\":1,\"m\":1,\"ties\":[1],\"discrepancy\":{\"num\":12,\"den\":16,"
        "\"value\":0.75}},\n"
        "  {\"n\":3,\"tau\":1,\"p\":1,\"m\":1,\"ties\":[1,2],\"discrepancy\":{\"num\":24,"
        "\"den\":36,\"value\":0.6666666666666666}},\n"
        "  "
        "{\"n\":5,\"tau\":2,\"p\":2,\"m\":1,\"ties\":[2,3],\"discrepancy\":{\"num\":44,"
        "\"den\":100,\"value\":0.44}}"
        "\n"
        "]\n";
    CHECK(format_table(sample(), TableFormat::json, kProvenance) == expected);
    // The printed value must read back as exactly K / 4n^2.
    CHECK(std::strtod("0.6666666666666666", nullptr) == 24.0 / 36.0);
}

TEST_CASE("table format: fractional tables carry p, m and the denominator",
          "[codegen][table][fractional]") {
    // n = 16, m = 8: tau = 49/8 with K = 1420 of 4 n^2 m = 8192 (checked
    // against the brute force in the optimizer tests); the values here are
    // typed in, so the formatter is checked, not the search.
    const std::vector<spiral::SearchResult> results{{16, 49, {49, 79}, 1420, 8}};
    CHECK(format_table(results, TableFormat::json, kProvenance) ==
          "[\n  {\"n\":16,\"tau\":6.125,\"p\":49,\"m\":8,\"ties\":[49,79],\"discrepancy\":{"
          "\"num\":1420,\"den\":8192,\"value\":0.17333984375}}\n]\n");
    CHECK(format_table(results, TableFormat::csv, kProvenance) ==
          "n,tau,ties,num,den,value\n16,49/8,49/8 79/8,1420,8192,0.17333984375\n");
    const std::string md = format_table(results, TableFormat::md, kProvenance);
    CHECK(md.find("| K/4n^2m |") != std::string::npos);
    CHECK(md.find("| 16 | 49/8 | 49/8, 79/8 | 1420/8192 |") != std::string::npos);
    const std::string cpp = format_table(results, TableFormat::cpp, kProvenance);
    CHECK(cpp.find("inline constexpr int kSpiralTurnsDenominator = 8;\n") != std::string::npos);
    CHECK(cpp.find(" 49\n") != std::string::npos);
    const std::string glsl = format_table(results, TableFormat::glsl, kProvenance);
    CHECK(glsl.find("#define SPIRAL_TURNS_DENOMINATOR 8\n") != std::string::npos);
    // Integer tables say nothing about a denominator.
    CHECK(format_table(sample(), TableFormat::cpp, kProvenance).find("Denominator") ==
          std::string::npos);
    const std::vector<spiral::SearchResult> mixed{{2, 1, {1}, 12, 1}, {3, 2, {2}, 40, 2}};
    CHECK_THROWS_AS(format_table(mixed, TableFormat::csv, kProvenance), std::invalid_argument);
}

TEST_CASE("table format: csv has a header row and space-separated ties", "[codegen][table]") {
    const std::string expected =
        "n,tau,ties,num,den,value\n"
        "2,1,1,12,16,0.75\n"
        "3,1,1 2,24,36,0.6666666666666666\n"
        "5,2,2 3,44,100,0.44\n";
    CHECK(format_table(sample(), TableFormat::csv, kProvenance) == expected);
}

TEST_CASE("table format: md is a Markdown table with K/4n^2 and its value", "[codegen][table]") {
    const std::string expected =
        "| n | tau | ties | K/4n^2 | value |\n"
        "|--:|--:|:--|--:|--:|\n"
        "| 2 | 1 | 1 | 12/16 | 0.75 |\n"
        "| 3 | 1 | 1, 2 | 24/36 | 0.6666666666666666 |\n"
        "| 5 | 2 | 2, 3 | 44/100 | 0.44 |\n";
    CHECK(format_table(sample(), TableFormat::md, kProvenance) == expected);
}

TEST_CASE("table format: cpp is a constexpr array indexed by n with 0 where nothing was computed",
          "[codegen][table]") {
    const std::string text = format_table(sample(), TableFormat::cpp, kProvenance);
    CHECK(text.rfind("// Spiral turns table (C++) -- generated by spiralgen; do not edit by hand.\n"
                     "// Command: `spiralgen table --min-n 2 --max-n 5 --format X`\n",
                     0) == 0);
    CHECK(text.find("for n = 2..5 (with gaps)") != std::string::npos);
    CHECK(text.find("#pragma once\n") != std::string::npos);
    CHECK(text.find("inline constexpr int kSpiralTurnsMinTaps = 2;\n") != std::string::npos);
    CHECK(text.find("inline constexpr int kSpiralTurnsMaxTaps = 5;\n") != std::string::npos);
    // Index:                                                 0  1  2  3  4  5
    CHECK(text.find("inline constexpr std::array<int, 6> kSpiralTurns = {\n"
                    "    /* 0 */ 0, 0, 1, 1, 0, 2\n"
                    "};\n") != std::string::npos);
}

TEST_CASE("table format: glsl is a const int array indexed by n", "[codegen][table]") {
    const std::string text = format_table(sample(), TableFormat::glsl, kProvenance);
    CHECK(text.rfind("// Spiral turns table (GLSL) -- generated by spiralgen", 0) == 0);
    CHECK(text.find("#define SPIRAL_TURNS_MIN_TAPS 2\n"
                    "#define SPIRAL_TURNS_MAX_TAPS 5\n"
                    "const int SPIRAL_TURNS[SPIRAL_TURNS_MAX_TAPS + 1] = int[](\n"
                    "    /* 0 */ 0, 0, 1, 1, 0, 2\n"
                    ");\n") != std::string::npos);
}

TEST_CASE("table format: long tables wrap at 16 entries with the first index of each row",
          "[codegen][table]") {
    std::vector<SearchResult> results;
    for (int n = 1; n <= 17; ++n) results.push_back(result(n, n, {n}, 4));
    const std::string text = format_table(results, TableFormat::glsl, kProvenance);
    CHECK(text.find("    /*  0 */ 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15,\n"
                    "    /* 16 */ 16, 17\n);") != std::string::npos);
    CHECK(text.find("(with gaps)") == std::string::npos);
}

TEST_CASE("table format: the provenance comment cannot be broken by odd characters",
          "[codegen][table]") {
    const Provenance odd{"spiralgen table\n#error injected \\"};
    const std::string text = format_table(sample(), TableFormat::glsl, odd);
    CHECK(text.find("// Command: `spiralgen table?#error injected \\`\n") != std::string::npos);
}

TEST_CASE("table format: format_table refuses empty or unordered results", "[codegen][table]") {
    CHECK_THROWS_AS(format_table({}, TableFormat::md, kProvenance), std::invalid_argument);
    CHECK_THROWS_AS(
        format_table({result(3, 1, {1}, 24), result(2, 1, {1}, 12)}, TableFormat::md, kProvenance),
        std::invalid_argument);
    CHECK_THROWS_AS(format_table({result(2, 1, {1}, 12), result(2, 1, {1}, 12)}, TableFormat::json,
                                 kProvenance),
                    std::invalid_argument);
    CHECK_THROWS_AS(format_table({result(0, 1, {1}, 0)}, TableFormat::cpp, kProvenance),
                    std::invalid_argument);
}

TEST_CASE("table format: format_table is deterministic", "[codegen][table]") {
    for (auto format : {TableFormat::cpp, TableFormat::glsl, TableFormat::json, TableFormat::csv,
                        TableFormat::md})
        CHECK(format_table(sample(), format, kProvenance) ==
              format_table(sample(), format, kProvenance));
}
