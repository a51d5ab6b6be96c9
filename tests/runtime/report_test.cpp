// The speed-against-error report: its error statistics against hand
// computation, its patterns against the optimizer's nesting of denominators
// and the golden-angle formula, a tiny end-to-end run, and the command's bad
// input handling.
#include "deepgi/context.hpp"
#include "deepgi/report.hpp"
#include "support/process.hpp"

#include <spiral/optimizer.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using deepgi::FloatImage;
namespace report = deepgi::report;

namespace {

std::vector<std::string> split(const std::string& line, char separator) {
    std::vector<std::string> fields;
    std::string field;
    std::istringstream in(line);
    while (std::getline(in, field, separator)) fields.push_back(field);
    if (!line.empty() && line.back() == separator) fields.push_back("");
    return fields;
}

}  // namespace

TEST_CASE("report: error statistics match a hand computation", "[report]") {
    const FloatImage estimate{2, 2, 1, {0.5f, 0.8f, 0.25f, 1.0f}};
    const FloatImage truth{2, 2, 1, {0.25f, 1.0f, 0.25f, 0.0f}};
    // The last pixel is masked out; errors are +0.25, -0.2, 0.
    const report::ErrorStats stats = report::compare_images(estimate, truth, {1, 1, 1, 0});
    CHECK(stats.pixels == 3);
    CHECK(stats.mae == Approx((0.25 + 0.2) / 3.0).epsilon(1e-6));
    CHECK(stats.rmse == Approx(std::sqrt((0.0625 + 0.04) / 3.0)).epsilon(1e-6));
    CHECK(stats.bias == Approx((0.25 - 0.2) / 3.0).epsilon(1e-6));

    // Three channels are averaged before comparing.
    const FloatImage colour{1, 1, 3, {0.0f, 0.3f, 0.6f}};
    const FloatImage grey{1, 1, 1, {0.5f}};
    const report::ErrorStats mixed = report::compare_images(colour, grey, {1});
    CHECK(mixed.bias == Approx(0.3 - 0.5).epsilon(1e-6));

    // Nothing to compare gives NaN, never a misleading zero.
    CHECK(std::isnan(report::compare_images(estimate, truth, {0, 0, 0, 0}).mae));
    CHECK_THROWS(report::compare_images(estimate, grey, {1, 1, 1, 1}));
    CHECK_THROWS(report::compare_images(estimate, truth, {1}));
}

TEST_CASE("report: patterns nest by denominator and follow the golden angle", "[report]") {
    for (int n : {8, 11, 16, 32}) {
        // p / 2m includes every p / m, so each finer optimum is at least as good.
        const double d1 = report::pattern_discrepancy("optimal", n);
        const double d2 = report::pattern_discrepancy("m2", n);
        const double d4 = report::pattern_discrepancy("m4", n);
        const double d8 = report::pattern_discrepancy("m8", n);
        CHECK(d2 <= d1);
        CHECK(d4 <= d2);
        CHECK(d8 <= d4);
        CHECK(report::pattern_turns("m4", n).m == 4);
        CHECK(report::pattern_discrepancy("tau1", n) >= d1);

        // Tap i of the golden-angle spiral sits at radius (i + 1/2) / n and
        // angle (i + 1/2) times the golden angle 2 pi (2 - phi).
        const report::Turns golden = report::pattern_turns("golden", n);
        const auto taps = spiral::codegen::spiral_taps(n, golden.p, golden.m);
        const double golden_angle = 2.0 * M_PI * (2.0 - (1.0 + std::sqrt(5.0)) / 2.0);
        // p / 2^20 is within 2^-21 of the true turns, which moves tap i by at
        // most 2 pi 2^-21 alpha_i; float storage adds half an ulp.
        for (int i = 0; i < n; ++i) {
            const double alpha = (i + 0.5) / n;
            const double margin = 2.0 * M_PI * std::ldexp(alpha, -21) + 1e-7;
            INFO("n = " << n << ", tap " << i);
            CHECK(std::abs(taps[i].x - alpha * std::cos(golden_angle * (i + 0.5))) <= margin);
            CHECK(std::abs(taps[i].y - alpha * std::sin(golden_angle * (i + 0.5))) <= margin);
        }
    }
    CHECK_THROWS(report::pattern_turns("fibonacci", 8));
}

TEST_CASE("report: a tiny run completes with one row per combination and error falling with taps",
          "[report][gl]") {
    deepgi::HeadlessContext context;
    const fs::path output = spiral::test::make_scratch_dir("deepgi-report-test");
    report::ReportOptions options;
    options.scenes = {"cornell"};
    options.taps = {4, 32};
    options.patterns = {"optimal", "golden"};
    options.layers = {1, 2};
    options.width = 96;
    options.height = 54;
    options.rays = 64;
    options.converged_taps = 128;
    options.warmup = 0;
    options.frames = 1;
    options.output = output;
    const report::ReportResult result = report::run_report(options);
    REQUIRE(result.rows.size() == 8);

    // Read the CSV back as a consumer would.
    std::istringstream csv(spiral::test::read_file(output / "report.csv"));
    std::string line;
    REQUIRE(std::getline(csv, line));
    const std::vector<std::string> header = split(line, ',');
    REQUIRE(header.size() == 4 + report::value_columns().size());
    CHECK(header[0] == "scene");
    std::map<std::string, std::size_t> column;
    for (std::size_t i = 0; i < header.size(); ++i) column[header[i]] = i;
    std::set<std::string> combinations;
    std::map<int, std::vector<double>> sampling_error;
    int rows = 0;
    while (std::getline(csv, line)) {
        const auto fields = split(line, ',');
        REQUIRE(fields.size() == header.size());
        ++rows;
        CHECK(fields[0] == "cornell");
        combinations.insert(fields[1] + "/" + fields[2] + "/" + fields[3]);
        const int taps = std::stoi(fields[2]);
        sampling_error[taps].push_back(std::stod(fields[column.at("conv_raw_mae")]));
        const double ms = std::stod(fields[column.at("sao_ms")]);
        CHECK(ms > 0.0);
        const double reference_mae = std::stod(fields[column.at("ref_blur_mae")]);
        CHECK(reference_mae >= 0.0);
        CHECK(reference_mae <= 1.0);
        CHECK(std::stod(fields[column.at("ref_pixels")]) > 100.0);
    }
    CHECK(rows == 8);
    CHECK(combinations.size() == 8);
    for (const char* expected : {"optimal/4/1", "optimal/4/2", "optimal/32/1", "optimal/32/2",
                                 "golden/4/1", "golden/4/2", "golden/32/1", "golden/32/2"}) {
        CHECK(combinations.count(expected) == 1);
    }
    auto mean = [](const std::vector<double>& v) {
        double sum = 0.0;
        for (double x : v) sum += x;
        return sum / double(v.size());
    };
    CHECK(mean(sampling_error[32]) < mean(sampling_error[4]));

    const std::string json = spiral::test::read_file(output / "report.json");
    std::size_t json_rows = 0;
    for (std::size_t at = json.find("\"scene\":"); at != std::string::npos;
         at = json.find("\"scene\":", at + 1))
        ++json_rows;
    CHECK(json_rows == 8);
    CHECK(fs::exists(output / "discrepancy.csv"));
    CHECK(fs::exists(output / "images" / "cornell-truth.pfm"));
    CHECK(fs::exists(output / "images" / "cornell-estimate.pfm"));
    fs::remove_all(output);
}

TEST_CASE("report: bad options exit 2 with one line and leave no output", "[report]") {
    const fs::path scratch = spiral::test::make_scratch_dir("deepgi-report-cli");
    const fs::path output = scratch / "out";
    const std::string program = DEEPGI_EXECUTABLE;
    for (const std::string& arguments :
         {std::string("--taps 0"), std::string("--taps 4,x"), std::string("--patterns fibonacci"),
          std::string("--layers 3"), std::string("--size 10by10"), std::string("--rays 0"),
          std::string("--scenes no-such-scene")}) {
        const auto run = spiral::test::run_command(
            program + " report " + arguments + " --no-plots --output '" + output.string() + "'");
        INFO(arguments << ": " << run.err);
        CHECK(run.status == 2);
        CHECK(spiral::test::count_lines(run.err) == 1);
        CHECK_FALSE(fs::exists(output));
    }
    const auto missing = spiral::test::run_command(program + " report --no-plots");
    CHECK(missing.status == 2);
    fs::remove_all(scratch);
}
