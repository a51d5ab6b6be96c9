// The table and discrepancy subcommands, driven through the real executable.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "help_check.hpp"
#include "process.hpp"
#include "spiral/optimizer.hpp"
#include "spiral/published.hpp"

using spiral::test::count_lines;
using spiral::test::run_command;

namespace {

const std::string kSpiralgen = SPIRALGEN_PATH;

spiral::test::ProcessResult spiralgen(const std::string& arguments) {
    std::string command_line = "'";
    command_line.append(kSpiralgen).append("' ").append(arguments);
    return run_command(command_line);
}

}  // namespace

TEST_CASE("spiralgen: table output is identical across runs and thread counts", "[cli][table]") {
    const auto serial = spiralgen("table --max-n 150 --format json --jobs 1");
    const auto parallel = spiralgen("table --max-n 150 --format json --jobs 3");
    const auto again = spiralgen("table --max-n 150 --format json");
    REQUIRE(serial.status == 0);
    CHECK(serial.err.empty());
    CHECK(serial.out == parallel.out);
    CHECK(serial.out == again.out);
    CHECK(count_lines(serial.out) >= 150);
}

TEST_CASE("spiralgen: table json carries the search's exact values", "[cli][table]") {
    const auto result = spiralgen("table --min-n 12 --max-n 12 --format json");
    REQUIRE(result.status == 0);
    const auto expected = spiral::search(12);
    std::string ties;
    for (int tau : expected.ties) {
        if (!ties.empty()) ties.push_back(',');
        ties.append(std::to_string(tau));
    }
    const std::string object =
        "{\"n\":12,\"tau\":" + std::to_string(expected.tau) +
        ",\"p\":" + std::to_string(expected.tau) + ",\"m\":1,\"ties\":[" + ties +
        "],\"discrepancy\":{\"num\":" + std::to_string(expected.scaled) + ",\"den\":576,";
    CHECK(result.out.find(object) != std::string::npos);
}

TEST_CASE("spiralgen: table --denominator searches fractional turns", "[cli][table][fractional]") {
    const auto result = spiralgen("table --min-n 16 --max-n 16 --denominator 8 --format json");
    REQUIRE(result.status == 0);
    // Confirmed by the brute force in fractional_test.cpp.
    CHECK(result.out.find("{\"n\":16,\"tau\":6.125,\"p\":49,\"m\":8,\"ties\":[49,79],"
                          "\"discrepancy\":{\"num\":1420,\"den\":8192,") != std::string::npos);
    const auto one = spiralgen("table --max-n 40 --denominator 4 --format csv --jobs 1");
    const auto three = spiralgen("table --max-n 40 --denominator 4 --format csv --jobs 3");
    REQUIRE(one.status == 0);
    CHECK(one.out == three.out);
    // --denominator 1 is the integer table, byte for byte, provenance included.
    CHECK(spiralgen("table --max-n 30 --format cpp --denominator 1").out ==
          spiralgen("table --max-n 30 --format cpp").out);
}

TEST_CASE("spiralgen: discrepancy --turns takes real turns and the golden angle",
          "[cli][discrepancy][fractional]") {
    // A decimal that is a short fraction is evaluated exactly: 6.125 = 49/8.
    const auto exact = spiralgen("discrepancy --n 16 --turns 6.125");
    REQUIRE(exact.status == 0);
    CHECK(exact.out.find("approximated by tau = 49/8") != std::string::npos);
    CHECK(exact.out.find("D(16, 49/8) = 1420 / 8192") != std::string::npos);
    // Integer turns agree with --tau.
    const auto seven = spiralgen("discrepancy --n 16 --turns 7");
    CHECK(seven.out.find("D(16, 7) = 192 / 1024") != std::string::npos);
    // Golden: tau = 16 (2 - phi) = 6.1114561800016824... The printed value must
    // lie within the stated bound of D at another rational, 6111456 / 10^6,
    // which is within 1.9e-7 of tau, so within 2 * 1.9e-7 in D (the Lipschitz
    // bound proved in discrepancy_command.cpp).
    const auto golden = spiralgen("discrepancy --n 16 --turns golden --format json");
    REQUIRE(golden.status == 0);
    const auto at = golden.out.find("\"value\":");
    REQUIRE(at != std::string::npos);
    const double value = std::stod(golden.out.substr(at + 8));
    const double nearby = spiral::discrepancy(16, 6111456, 1000000).value();
    CHECK(std::abs(value - nearby) <= 4e-7);
    CHECK(std::abs(value - nearby) > 0);  // a different rational, not the same number
}

TEST_CASE("spiralgen: a bad --denominator leaves no file", "[cli][errors][fractional]") {
    const auto path = std::filesystem::temp_directory_path() / "spiralgen_denominator_test.md";
    std::filesystem::remove(path);
    const auto result = spiralgen("table --max-n 8 --denominator 0 --out '" + path.string() + "'");
    CHECK(result.status == 2);
    CHECK(result.err.find("--denominator 0") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(path));
    const auto overflow = spiralgen("table --max-n 65535 --denominator 67110913");
    CHECK(overflow.status == 2);
    CHECK(overflow.err.find("2^60") != std::string::npos);
    CHECK(overflow.err.find("67110912") != std::string::npos);
}

TEST_CASE("spiralgen: discrepancy reports the exact fraction and the worst sector",
          "[cli][discrepancy]") {
    const auto d = spiral::discrepancy(11, 3);
    const auto text = spiralgen("discrepancy --n 11 --tau 3");
    REQUIRE(text.status == 0);
    CHECK(text.out.find("D(11, 3) = " + std::to_string(d.scaled) + " / 484") != std::string::npos);
    CHECK(text.out.find("worst sector") != std::string::npos);

    const auto json = spiralgen("discrepancy --n 11 --tau 3 --format json");
    REQUIRE(json.status == 0);
    CHECK(json.out.find("\"num\":" + std::to_string(d.scaled) + ",\"den\":484") !=
          std::string::npos);
    CHECK(json.out.find("\"count\":" + std::to_string(d.worst.count)) != std::string::npos);
}

TEST_CASE("spiralgen: bad input gives one line on stderr and exit status 2", "[cli][errors]") {
    const std::string arguments = GENERATE(
        as<std::string>{}, "discrepancy --n abc --tau 3", "discrepancy --n 0 --tau 3",
        "discrepancy --n 70000 --tau 3", "discrepancy --n 11 --tau 0",
        "discrepancy --n 11 --tau -4", "discrepancy --n 11",
        "discrepancy --n 11 --tau 3 --format xml", "table --min-n 0", "table --max-n 99999",
        "table --min-n 10 --max-n 5", "table --format yaml", "table --jobs -2", "table --max-n x",
        "table --out /nonexistent-dir/sub/table.md", "frobnicate", "",
        "table --max-n 8 --denominator 0", "table --max-n 8 --denominator -2",
        "table --max-n 8 --denominator eight", "table --max-n 8 --denominator 2.5",
        "table --max-n 65535 --denominator 67110913", "table --max-n 2 --denominator 999999999",
        "discrepancy --n 16 --turns 0", "discrepancy --n 16 --turns -2",
        "discrepancy --n 16 --turns 16.5", "discrepancy --n 16 --turns nan",
        "discrepancy --n 16 --turns inf", "discrepancy --n 16 --turns six",
        "discrepancy --n 16 --turns 3 --tau 3", "discrepancy --n 16 --turns 1e-30", "ties",
        "ties --n 0", "ties --n 70000", "ties --n 9 --format json", "ties --n 9 --denominator 0");
    INFO("spiralgen " << arguments);
    const auto result = spiralgen(arguments);
    CHECK(result.status == 2);
    CHECK(count_lines(result.err) == 1);
    CHECK(result.err.rfind("spiralgen: error: ", 0) == 0);
    CHECK(result.out.empty());
}

TEST_CASE("spiralgen: without a known subcommand it names every subcommand", "[cli][errors]") {
    const auto none = spiralgen("");
    CHECK(none.status == 2);
    CHECK(none.err ==
          "spiralgen: error: a subcommand is required: table, discrepancy, ties, header, blur "
          "(spiralgen --help describes them)\n");
    const auto unknown = spiralgen("frobnicate --n 3");
    CHECK(unknown.status == 2);
    CHECK(unknown.err ==
          "spiralgen: error: 'frobnicate' is not a subcommand; the subcommands are table, "
          "discrepancy, ties, header, blur (spiralgen --help describes them)\n");
}

TEST_CASE("spiralgen: --help works on every subcommand", "[cli]") {
    const std::string command = GENERATE(as<std::string>{}, "table", "discrepancy", "ties");
    const auto result = spiralgen(command + " --help");
    CHECK(result.status == 0);
    CHECK(result.out.find("--format") != std::string::npos);
}

TEST_CASE("spiralgen: every option's help shows its default, without parser notation",
          "[cli][help]") {
    const std::string command =
        GENERATE(as<std::string>{}, "table", "discrepancy", "header", "blur");
    const auto result = spiralgen(command + " --help");
    REQUIRE(result.status == 0);
    INFO(command << " --help");
    CHECK(spiral::test::help_entries(result.out).size() >= 4);
    for (const auto& bad : spiral::test::undocumented_options(result.out)) {
        INFO(bad);
        CHECK(false);
    }
    const auto top = spiralgen("--help");
    for (const char* name : {"table", "discrepancy", "header", "blur"})
        CHECK(top.out.find(name) != std::string::npos);
}

TEST_CASE("spiralgen: --out is written atomically and a failing run leaves no file",
          "[cli][atomic]") {
    const auto dir = spiral::test::make_scratch_dir("spiralgen-cli");
    const auto out = dir / "table.md";

    SECTION("a good run writes exactly what stdout would show") {
        const auto to_file = spiralgen("table --max-n 40 --out '" + out.string() + "'");
        const auto to_stdout = spiralgen("table --max-n 40");
        REQUIRE(to_file.status == 0);
        CHECK(to_file.out.empty());
        CHECK(spiral::test::read_file(out) == to_stdout.out);
    }
    SECTION("a failing run creates nothing") {
        const auto result =
            spiralgen("table --max-n 40 --format nope --out '" + out.string() + "'");
        CHECK(result.status == 2);
        CHECK_FALSE(std::filesystem::exists(out));
    }
    SECTION("a failing run keeps the previous file intact") {
        REQUIRE(spiralgen("table --max-n 20 --out '" + out.string() + "'").status == 0);
        const auto before = spiral::test::read_file(out);
        CHECK(spiralgen("table --max-n 0 --out '" + out.string() + "'").status == 2);
        CHECK(spiral::test::read_file(out) == before);
    }
    // No temporary may be left next to the output either way.
    int entries = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++entries;
    CHECK(entries <= 1);
    std::filesystem::remove_all(dir);
}

namespace {

// The smallest K over every integer tau in [1, n], by the exact evaluator
// alone (no search, no bounds).
std::int64_t minimum_by_evaluator(int n) {
    std::int64_t best = -1;
    for (int tau = 1; tau <= n; ++tau) {
        const std::int64_t k = spiral::discrepancy(n, tau).scaled;
        if (best < 0 || k < best) best = k;
    }
    return best;
}

}  // namespace

TEST_CASE("spiralgen: --compare-published verdicts agree with the exact evaluator",
          "[cli][table][published]") {
    const auto result = spiralgen("table --compare-published --format csv");
    REQUIRE(result.status == 0);
    CHECK(result.err.empty());
    const auto published = spiral::published_turns();
    REQUIRE(count_lines(result.out) == int(published.size()) + 1);
    std::vector<std::int64_t> minimum(published.size() + 2, -1);
    for (std::size_t n = 1; n < minimum.size(); ++n) minimum[n] = minimum_by_evaluator(int(n));

    std::istringstream lines(result.out);
    std::string line;
    std::getline(lines, line);  // header
    int ties = 0;
    for (int n = 1; n <= int(published.size()); ++n) {
        REQUIRE(std::getline(lines, line));
        const int tau = published[std::size_t(n - 1)];
        const std::int64_t k = spiral::discrepancy(n, tau).scaled;
        std::string verdict = "worse";
        std::string optimal_for = "0";
        if (k == minimum[std::size_t(n)]) {
            verdict = "ties";
            optimal_for = "0";
        } else {
            for (int neighbour : {n - 1, n + 1}) {
                if (neighbour >= 1 &&
                    spiral::discrepancy(neighbour, tau).scaled == minimum[std::size_t(neighbour)]) {
                    verdict = "one-off";
                    optimal_for = std::to_string(neighbour);
                    break;
                }
            }
        }
        ties += verdict == "ties";
        std::ostringstream start, end;
        start << n << ',' << tau << ',' << k << ',';
        end << ',' << minimum[std::size_t(n)] << ',' << 4 * n * n << ',' << verdict << ','
            << optimal_for;
        INFO("n = " << n << ": " << line);
        CHECK(line.rfind(start.str(), 0) == 0);
        CHECK(line.find(end.str()) != std::string::npos);
    }
    // The paper's own example: tau = 7 for 9 taps is a minimiser (docs/optimizer.md),
    // but the published entry for n = 9 is 2, also a minimiser.
    CHECK(published[8] == 2);
    CHECK(ties > 0);

    const auto md = spiralgen("table --compare-published");
    REQUIRE(md.status == 0);
    CHECK(md.out.find("Listing 3") != std::string::npos);
    CHECK(md.out.find(std::to_string(ties) + " of " + std::to_string(published.size()) +
                      " published values tie the optimum") != std::string::npos);

    const auto refused = spiralgen("table --compare-published --max-n 40");
    CHECK(refused.status == 2);
    CHECK(refused.err.find("--max-n") != std::string::npos);
}

TEST_CASE("spiralgen: ties lists every minimiser with its profile and marks the search's pick",
          "[cli][ties]") {
    const int n = GENERATE(6, 11, 49);
    const auto result = spiralgen("ties --n " + std::to_string(n) + " --format csv");
    REQUIRE(result.status == 0);
    const auto optimum = spiral::search(n);
    std::istringstream lines(result.out);
    std::string line;
    std::getline(lines, line);
    CHECK(line == "n,tau,p,m,picked,mirror,K,profile");
    std::vector<int> listed;
    int picked = 0;
    while (std::getline(lines, line)) {
        std::istringstream fields(line);
        std::string n_text, tau, p, m, pick, mirror, k, profile;
        std::getline(fields, n_text, ',');
        std::getline(fields, tau, ',');
        std::getline(fields, p, ',');
        std::getline(fields, m, ',');
        std::getline(fields, pick, ',');
        std::getline(fields, mirror, ',');
        std::getline(fields, k, ',');
        std::getline(fields, profile);
        listed.push_back(std::stoi(p));
        if (pick == "1") picked = std::stoi(p);
        CHECK(std::stoi(mirror) == n - std::stoi(p));
        CHECK(std::stoll(k) == optimum.scaled);
        // The profile as the library computes it, k = 0..n.
        std::ostringstream expected;
        const auto entries = spiral::band_profile(n, std::stoi(p));
        for (std::size_t i = 0; i < entries.size(); ++i) expected << (i ? " " : "") << entries[i];
        CHECK(profile == expected.str());
    }
    CHECK(listed == optimum.ties);
    CHECK(picked == optimum.tau);
}
