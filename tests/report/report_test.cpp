// The speed-against-error report: its error statistics against hand
// computation, its patterns against the optimizer's nesting of denominators
// and the golden-angle formula, a tiny end-to-end run, and the command's bad
// input handling.
#include "deepgi/context.hpp"
#include "deepgi/report.hpp"
#include "support/process.hpp"
#include "support/skip.hpp"

#include <spiral/optimizer.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

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

// One CSV record (RFC 4180: quoted fields may hold commas and doubled quotes).
std::vector<std::string> split(const std::string& line, char separator) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
                fields.back() += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                fields.back() += c;
            }
        } else if (c == '"') {
            quoted = true;
        } else if (c == separator) {
            fields.emplace_back();
        } else {
            fields.back() += c;
        }
    }
    return fields;
}

// Header and rows of a CSV file, each row as column name -> field.
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& path) {
    std::istringstream in(spiral::test::read_file(path));
    std::string line;
    std::vector<std::map<std::string, std::string>> rows;
    if (!std::getline(in, line)) return rows;
    const std::vector<std::string> header = split(line, ',');
    while (std::getline(in, line)) {
        const std::vector<std::string> fields = split(line, ',');
        REQUIRE(fields.size() == header.size());
        std::map<std::string, std::string> row;
        for (std::size_t i = 0; i < header.size(); ++i) row[header[i]] = fields[i];
        rows.push_back(row);
    }
    return rows;
}

std::size_t count_of(const std::string& text, const std::string& what) {
    std::size_t count = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
        ++count;
    return count;
}

// `deepgi report` as a user runs it, on one scene at a tiny size with one
// pattern, one layer count and the solid angle; `arguments` adds the rest.
spiral::test::ProcessResult run_tiny_report(const std::string& arguments, const fs::path& output) {
    return spiral::test::run_command(
        std::string(DEEPGI_EXECUTABLE) +
        " report --scenes cornell --patterns optimal --layers 1 --ao-methods solid-angle "
        "--size 96x54 --rays 32 --converged-taps 64 --warmup 0 --frames 1 --no-plots " +
        arguments + " --output '" + output.string() + "'");
}

}  // namespace

TEST_CASE("report: CSV fields with commas and quotes are quoted and read back", "[report]") {
    CHECK(report::csv_field("cornell") == "cornell");
    CHECK(report::csv_field("llvmpipe (LLVM 15.0.6, 256 bits)") ==
          "\"llvmpipe (LLVM 15.0.6, 256 bits)\"");
    CHECK(report::csv_field("a \"b\"") == "\"a \"\"b\"\"\"");
    const std::string line =
        report::csv_field("x,y") + "," + report::csv_field("say \"hi\"") + ",3";
    CHECK(split(line, ',') == std::vector<std::string>{"x,y", "say \"hi\"", "3"});
}

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

TEST_CASE(
    "report: each repeat starts the temporal sequence at the smallest power of two "
    "that holds its frames",
    "[report]") {
    // A run of 2^m Sobol frames is a net only from a multiple of 2^m on, so a
    // repeat that started anywhere else would be stratified worse than
    // repeat 0 and widen the spread the summary compares with.
    // The frames are the timed ones after the warmup, at least the 9 of the
    // accumulated columns, and the radiosity section's still run.
    for (int warmup : {0, 1, 3, 20}) {
        for (int frames : {1, 2, 7, 8, 15, 16, 100, 2001}) {
            for (int still : {0, 9, 64, 100, 1024}) {
                report::ReportOptions options;
                options.warmup = warmup;
                options.frames = frames;
                options.radiosity_frames = still;
                const int needed = std::max({9, 1 + warmup + frames, still});
                const int stride = report::repeat_offset(options, 1);
                CAPTURE(warmup, frames, still, stride);
                CHECK((stride & (stride - 1)) == 0);
                CHECK(stride >= needed);
                CHECK(stride / 2 < needed);
                CHECK(report::repeat_offset(options, 0) == 0);
                CHECK(report::repeat_offset(options, 15) == 15 * stride);
            }
        }
    }
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
    // The march runs once per layer count, at the tap count nearest the
    // image's 11 (its radiosity gather still reads the taps).
    options.ao_methods = {deepgi::AoMethod::solid_angle, deepgi::AoMethod::march};
    options.width = 96;
    options.height = 54;
    options.rays = 64;
    options.converged_taps = 128;
    options.warmup = 0;
    options.frames = 1;
    // The radiosity section's still run, shorter than its default 64 frames
    // for time; at 32 taps, the run's nearest to the renderer's 19.
    options.radiosity_frames = 24;
    // Two repeats (the default), and the extras, asked for.
    REQUIRE(options.repeats == 2);
    options.stability = true;
    options.float_check = true;
    options.float_max_n = 64;
    options.output = output;
    const report::ReportResult result = report::run_report(options);
    REQUIRE(result.rows.size() == 20);
    const std::string device = deepgi::query_context_info().renderer;
    REQUIRE_FALSE(device.empty());

    // Read the CSV back as a consumer would.
    std::istringstream csv(spiral::test::read_file(output / "report.csv"));
    std::string line;
    REQUIRE(std::getline(csv, line));
    const std::vector<std::string> header = split(line, ',');
    REQUIRE(header.size() == 6 + report::value_columns().size());
    CHECK(header[0] == "scene");
    CHECK(header[4] == "ao_method");
    CHECK(header[5] == "device");
    std::map<std::string, std::size_t> column;
    for (std::size_t i = 0; i < header.size(); ++i) column[header[i]] = i;
    std::set<std::string> combinations;
    // Each combination's first-frame raw error against the truth, per repeat.
    std::map<std::string, std::map<int, double>> repeat_error;
    std::map<int, std::vector<double>> sampling_error;
    // Each stage's error against the ray-traced truth, summed over the rows.
    std::map<std::string, double> stage_error;
    // The same on the rows of the still run, after 9 and after 24 frames.
    std::map<std::string, double> still_rows_error;
    // The share of the truth no layer holds, per layer count (the same
    // truth in every row).
    std::map<int, std::set<double>> unheld_share;
    // ref_open_blur_below of each method's image row (optimal, 4 taps, two layers).
    std::map<std::string, double> open_blur_below;
    int rows = 0;
    while (std::getline(csv, line)) {
        const auto fields = split(line, ',');
        REQUIRE(fields.size() == header.size());
        ++rows;
        CHECK(fields[0] == "cornell");
        CHECK(fields[5] == device);  // the context that timed the row labels it
        const std::string& method = fields[4];
        const std::string combination =
            method + "/" + fields[1] + "/" + fields[2] + "/" + fields[3];
        combinations.insert(combination);
        const int offset = std::stoi(fields[column.at("temporal_offset")]);
        // repeat_offset: the 24 frames of the still run, more than the 9 a
        // repeat needs at --warmup 0 --frames 1, rounded up to the power of
        // two 32 where a Sobol net starts.
        CHECK((offset == 0 || offset == 32));
        CHECK(report::repeat_offset(options, offset / 32) == offset);
        // The repeat's per-pixel rotation field: repeat 0 the shipped one.
        CHECK(std::stoi(fields[column.at("rotation_seed")]) ==
              report::repeat_rotation_seed(offset / 32));
        CHECK(report::repeat_rotation_seed(offset / 32) == offset / 32);
        repeat_error[combination][offset] = std::stod(fields[column.at("ref_raw_mae")]);
        const int taps = std::stoi(fields[2]);
        // The march gathers no taps, so it has no converged AO to compare with.
        if (method == "march") {
            CHECK(fields[column.at("conv_raw_mae")].empty());
            CHECK(fields[column.at("conv_blur_mae")].empty());
            CHECK_FALSE(fields[column.at("rad_conv_raw_rel_mae")].empty());
        } else {
            sampling_error[taps].push_back(std::stod(fields[column.at("conv_raw_mae")]));
        }
        // Open pixels below 0.99 are a subset of the open pixels.
        const double open = std::stod(fields[column.at("ref_open_pixels")]);
        CHECK(open > 0.0);
        // Those in open surroundings are a subset of them.
        for (const char* stage : {"raw", "blur", "accum"}) {
            INFO(stage);
            const double below =
                std::stod(fields[column.at(fmt::format("ref_open_{}_below", stage))]);
            const double core =
                std::stod(fields[column.at(fmt::format("ref_open_core_{}_below", stage))]);
            CHECK(below >= 0.0);
            CHECK(below <= open);
            CHECK(core >= 0.0);
            CHECK(core <= below);
        }
        if (fields[1] == "optimal" && taps == 4 && fields[3] == "2" && offset == 0)
            open_blur_below[method] = std::stod(fields[column.at("ref_open_blur_below")]);
        // Every timing column names a pass the frame timed: none is empty.
        for (const auto& [name, index] : column) {
            if (!name.ends_with("_ms")) continue;
            INFO(name);
            REQUIRE_FALSE(fields[index].empty());
            CHECK(std::stod(fields[index]) > 0.0);
        }
        CHECK(column.count("blur_ms") == 1);
        const double reference_mae = std::stod(fields[column.at("ref_blur_mae")]);
        CHECK(reference_mae >= 0.0);
        CHECK(reference_mae <= 1.0);
        CHECK(std::stod(fields[column.at("ref_pixels")]) > 100.0);
        for (const char* stage :
             {"ref_raw_mae", "ref_temporal_mae", "ref_accum_mae", "rad_ref_raw_rel_mae",
              "rad_ref_blur_rel_mae", "rad_ref_temporal_rel_mae", "rad_ref_accum_rel_mae"}) {
            INFO(stage);
            REQUIRE_FALSE(fields[column.at(stage)].empty());
            const double error = std::stod(fields[column.at(stage)]);
            CHECK(std::isfinite(error));
            CHECK(error >= 0.0);
            stage_error[stage] += error;
        }
        // Radiosity against the visible truth V, part of the whole truth W
        // (every part of the split is non-negative): the share s = 1 -
        // mean V / mean W lies in [0, 1), and the relative biases of one
        // estimate E against both are tied by (E - V) / V = (b_W + s) / (1 - s),
        // with b_W = (E - W) / W; a mask or a mean taken apart would break it.
        // The lengths every row rendered at: the library's defaults.
        CHECK(std::stod(fields[column.at("ao_radius")]) == deepgi::RenderSettings{}.ao.radius);
        CHECK(std::stod(fields[column.at("radiosity_radius")]) ==
              deepgi::RenderSettings{}.radiosity.radius);
        const double share = std::stod(fields[column.at("rad_unheld_share")]);
        CHECK(share >= 0.0);
        CHECK(share < 1.0);
        unheld_share[std::stoi(fields[3])].insert(share);
        // The still run: on the first method's optimal rows at 32 taps only.
        const bool still_row = method == "solid-angle" && fields[1] == "optimal" && taps == 32;
        CHECK(fields[column.at("rad_still_frames")] == (still_row ? "24" : ""));
        std::vector<const char*> stages = {"blur", "accum"};
        if (still_row) {
            stages.push_back("still");
            for (const char* stage : {"rad_ref_accum_rel_mae", "rad_ref_still_rel_mae",
                                      "rad_vis_accum_rel_mae", "rad_vis_still_rel_mae"})
                still_rows_error[stage] += std::stod(fields[column.at(stage)]);
        } else {
            for (const char* stage : {"ref", "vis"}) {
                for (const char* stat : {"mae", "rmse", "bias"})
                    CHECK(
                        fields[column.at(fmt::format("rad_{}_still_rel_{}", stage, stat))].empty());
            }
        }
        for (const char* stage : stages) {
            INFO(stage);
            const double whole =
                std::stod(fields[column.at(fmt::format("rad_ref_{}_rel_bias", stage))]);
            const double visible =
                std::stod(fields[column.at(fmt::format("rad_vis_{}_rel_bias", stage))]);
            CHECK(visible == Approx((whole + share) / (1.0 - share)).margin(1e-6));
            CHECK(std::stod(fields[column.at(fmt::format("rad_vis_{}_rel_mae", stage))]) >= 0.0);
        }
    }
    // One truth per layer count, and a second layer holds at least what the
    // first does.
    REQUIRE(unheld_share[1].size() == 1);
    REQUIRE(unheld_share[2].size() == 1);
    CHECK(*unheld_share[2].begin() <= *unheld_share[1].begin());
    // Nine frames of a still camera average nine rotations, so
    // the temporal filters' history is nearer the truth than a first frame's
    // raw gather, for AO and for radiosity alike.
    CHECK(stage_error["ref_temporal_mae"] < stage_error["ref_raw_mae"]);
    CHECK(stage_error["rad_ref_temporal_rel_mae"] < stage_error["rad_ref_raw_rel_mae"]);
    // And 24 frames keep less of the gather's noise than 9, against either truth.
    CHECK(still_rows_error["rad_ref_still_rel_mae"] < still_rows_error["rad_ref_accum_rel_mae"]);
    CHECK(still_rows_error["rad_vis_still_rel_mae"] < still_rows_error["rad_vis_accum_rel_mae"]);
    CHECK(rows == 20);
    CHECK(combinations.size() == 10);
    // Each combination twice, and the other temporal offset really samples
    // differently: the repeats' errors differ (the spread is not zero).
    for (const auto& [combination, errors] : repeat_error) {
        INFO(combination);
        REQUIRE(errors.size() == 2);
        CHECK(errors.at(0) != errors.at(32));
    }
    for (const char* expected :
         {"solid-angle/optimal/4/1", "solid-angle/optimal/4/2", "solid-angle/optimal/32/1",
          "solid-angle/optimal/32/2", "solid-angle/golden/4/1", "solid-angle/golden/4/2",
          "solid-angle/golden/32/1", "solid-angle/golden/32/2", "march/optimal/4/1",
          "march/optimal/4/2"}) {
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
    CHECK(json_rows == 20);
    CHECK(count_of(json, "\"device\":") == 20);
    CHECK(json.find("\"repeats\":2,") != std::string::npos);
    CHECK(json.find("\"lengths\":\"library\",") != std::string::npos);
    CHECK(json.find("\"radiosity_frames\":24,\"radiosity_taps\":32,") != std::string::npos);
    // Four rows of the march, and its half of the stability rows (checked below).
    const std::string rows_json = json.substr(0, json.find("\"stability\":"));
    CHECK(count_of(rows_json, "\"ao_method\":\"march\"") == 4);
    CHECK(fs::exists(output / "discrepancy.csv"));
    // The tie table: both tap counts have several minimisers (4: 1 and 3).
    const auto ties = read_csv(output / "ties.csv");
    REQUIRE(ties.size() == 2);
    CHECK(ties[0].at("n") == "4");
    CHECK(ties[0].at("ties") == "1 3");
    CHECK(ties[1].at("n") == "32");
    CHECK(ties[1].at("verdict").empty());  // no --ties-from
    // The images of each method, counted again from the files: the open
    // pixels below 0.99 agree with the row the images came from.
    const deepgi::FloatImage truth = deepgi::read_pfm(output / "images" / "cornell-truth.pfm");
    for (const char* method : {"solid-angle", "march"}) {
        INFO(method);
        const auto path = output / "images" / fmt::format("cornell-estimate-{}.pfm", method);
        REQUIRE(fs::exists(path));
        const deepgi::FloatImage estimate = deepgi::read_pfm(path);
        REQUIRE(estimate.pixels.size() == truth.pixels.size());
        int below = 0;
        for (std::size_t i = 0; i < truth.pixels.size(); ++i)
            below += truth.pixels[i] >= 0.9999f && estimate.pixels[i] < 0.99f;
        CHECK(double(below) == open_blur_below.at(method));
    }

    // The numerical hard cases: one row per check, all passing.
    // The expected count follows from the documented case set, once per
    // estimator of the run.
    const deepgi::hard_cases::Parameters cases;
    const std::size_t layer_counts = cases.layers.size();
    const std::size_t per_method =
        cases.scaled_scenes.size() * cases.scales.size() * 2     // raw and blurred
        + cases.far_pitches.size() * cases.far_radii.size() * 2  // lowest AV, floor share
        + cases.grazing_pitches.size() * layer_counts            // lowest AV
        + 3 * (layer_counts * cases.guard_radii.size() + 1)      // three edges, + depth ratio
        + cases.tiny_sizes.size() * cases.tiny_scenes.size();    // invalid pixels
    const std::size_t expected_stability = per_method * options.ao_methods.size();
    const auto stability = read_csv(output / "stability.csv");
    CHECK(stability.size() == expected_stability);
    CHECK(result.stability.size() == expected_stability);
    std::map<std::string, std::size_t> rows_per_method;
    for (const auto& row : stability) ++rows_per_method[row.at("ao_method")];
    for (deepgi::AoMethod method : options.ao_methods)
        CHECK(rows_per_method[std::string(deepgi::to_string(method))] == per_method);
    std::map<std::string, int> families;
    for (const auto& row : stability) {
        INFO(row.at("case") << ": " << row.at("quantity") << " = " << row.at("value"));
        // The pass column agrees with the value and bound written beside it.
        const double value = std::stod(row.at("value"));
        const double tolerance = std::stod(row.at("tolerance"));
        REQUIRE((row.at("test") == "<=" || row.at("test") == ">="));
        const bool holds = row.at("test") == "<=" ? value <= tolerance : value >= tolerance;
        CHECK(row.at("pass") == (holds ? "1" : "0"));
        CHECK(row.at("pass") == "1");
        const std::string& name = row.at("case");
        for (const char* family :
             {"scale ", "far floor", "grazing floor", "guard-band edge", "1x1", "3x2"})
            if (name.rfind(family, 0) == 0) ++families[family];
    }
    CHECK(families.size() == 6);
    // The scale cases compare against a tolerance of 1e-3 at most, as documented.
    for (const auto& row : stability)
        if (row.at("case").rfind("scale ", 0) == 0) CHECK(std::stod(row.at("tolerance")) <= 1e-3);
    CHECK(count_of(json, "\"case\":") == expected_stability);
    CHECK(count_of(json, "\"ao_method\":\"march\",\"case\":") == per_method);

    // Exact against double search: one row per n, checked against the optimizer.
    const auto choices = read_csv(output / "float_vs_exact.csv");
    REQUIRE(choices.size() == 64);
    int differing = 0;
    for (std::size_t i = 0; i < choices.size(); ++i) {
        const auto& row = choices[i];
        const int n = std::stoi(row.at("n"));
        INFO("n = " << n);
        CHECK(n == int(i) + 1);
        const spiral::SearchResult exact = spiral::search(n);
        CHECK(std::stoi(row.at("exact_tau")) == exact.tau);
        CHECK(std::stoll(row.at("exact_K")) == exact.scaled);
        const int float_tau = std::stoi(row.at("float_tau"));
        CHECK(std::stoll(row.at("float_tau_exact_K")) == spiral::discrepancy_scaled(n, float_tau));
        CHECK(row.at("differs") == (float_tau != exact.tau ? "1" : "0"));
        differing += float_tau != exact.tau;
    }
    CHECK(differing > 0);  // n = 7 differs (docs/optimizer.md)
    CHECK(choices[6].at("differs") == "1");
    CHECK(json.find(fmt::format("\"differing\":{},", differing)) != std::string::npos);

    // The summary states the extras that were asked for, its counts
    // recomputed here from the CSV files the report wrote.
    if (fs::exists("/usr/bin/python3")) {
        const auto plot = spiral::test::run_command("/usr/bin/python3 '" +
                                                    std::string(DEEPGI_PLOT_REPORT_SCRIPT) +
                                                    "' --summary-only '" + output.string() + "'");
        INFO(plot.err);
        REQUIRE(plot.status == 0);
        const std::string summary = spiral::test::read_file(output / "summary.md");
        INFO(summary);
        std::size_t passing = 0;
        for (const auto& row : stability) passing += row.at("pass") == "1";
        CHECK(summary.find("## Numerical stability") != std::string::npos);
        CHECK(summary.find(fmt::format("**{} of {} checks pass**", passing, stability.size())) !=
              std::string::npos);
        CHECK(summary.find(fmt::format("exact integer search at **{}** n", differing)) !=
              std::string::npos);
    }
    fs::remove_all(output);
}

TEST_CASE("report: extras run only when asked, and a tiny run says what it cannot conclude",
          "[report][gl]") {
    // The command as a user runs it, with nothing asked beyond the rows.
    const fs::path output = spiral::test::make_scratch_dir("deepgi-report-defaults");
    const auto run = run_tiny_report("--taps 4,8", output);
    INFO(run.out << run.err);
    REQUIRE(run.status == 0);
    CHECK_FALSE(fs::exists(output / "stability.csv"));
    CHECK_FALSE(fs::exists(output / "float_vs_exact.csv"));
    CHECK(read_csv(output / "report.csv").size() == 4);  // 2 tap counts x 2 repeats
    const std::string json = spiral::test::read_file(output / "report.json");
    CHECK(json.find("\"stability\":[\n]") != std::string::npos);
    CHECK(json.find("\"max_n\":0,") != std::string::npos);
    if (!fs::exists("/usr/bin/python3"))
        spiral::test::skip_test("python3 is missing (the summary is written by a Python script)");
    const auto plot =
        spiral::test::run_command("/usr/bin/python3 '" + std::string(DEEPGI_PLOT_REPORT_SCRIPT) +
                                  "' --summary-only '" + output.string() + "'");
    INFO(plot.err);
    REQUIRE(plot.status == 0);
    const std::string summary = spiral::test::read_file(output / "summary.md");
    INFO(summary);
    CHECK(summary.find("## Numerical stability") == std::string::npos);
    CHECK(summary.find("checks pass") == std::string::npos);
    // One pattern at one study tap count: no rank correlation, and why.
    CHECK(summary.find("This run cannot say: a rank correlation needs at least 3 patterns") !=
          std::string::npos);
    CHECK(summary.find("Spearman") == std::string::npos);
    CHECK(summary.find("only optimal tau (m = 1) was run, so no pattern is ranked") !=
          std::string::npos);
    fs::remove_all(output);
}

TEST_CASE("report: with --lengths auto every row renders at the scene's own lengths",
          "[report][gl]") {
    const fs::path output = spiral::test::make_scratch_dir("deepgi-report-lengths");
    const auto run =
        run_tiny_report("--lengths auto --taps 4 --repeats 1 --no-reflections", output);
    INFO(run.out << run.err);
    REQUIRE(run.status == 0);
    const auto rows = read_csv(output / "report.csv");
    REQUIRE(rows.size() == 1);
    // Cornell is a 2 m cube about the origin: bounding radius sqrt(3). The
    // AO radius is a tenth of it and the radiosity radius 0.6 of it, below
    // its cap of 0.75 of the smallest extent (docs/deepgi.md, "Scene scale").
    CHECK(std::stod(rows[0].at("ao_radius")) == Approx(0.1 * std::sqrt(3.0)).epsilon(1e-5));
    CHECK(std::stod(rows[0].at("radiosity_radius")) == Approx(0.6 * std::sqrt(3.0)).epsilon(1e-5));
    CHECK(spiral::test::read_file(output / "report.json").find("\"lengths\":\"auto\",") !=
          std::string::npos);
    fs::remove_all(output);
}

TEST_CASE("report: bad options exit 2 with one line and leave no output", "[report]") {
    const fs::path scratch = spiral::test::make_scratch_dir("deepgi-report-cli");
    const fs::path output = scratch / "out";
    const std::string program = DEEPGI_EXECUTABLE;
    for (const std::string& arguments :
         {std::string("--taps 0"), std::string("--taps 4,x"), std::string("--patterns fibonacci"),
          std::string("--layers 3"), std::string("--size 10by10"), std::string("--rays -1"),
          std::string("--float-check --float-max-n 0"),
          std::string("--float-check --float-max-n 5000"),
          std::string("--float-max-n 64"),  // without --float-check: refused, not ignored
          std::string("--no-stability"),    // the hard cases are off unless --stability
          std::string("--repeats 0"), std::string("--repeats 17"),
          std::string("--ao-methods horizon"), std::string("--ao-methods march,march"),
          std::string("--ties-from no-such-verdicts.csv"), std::string("--scenes no-such-scene"),
          std::string("--lengths metres"), std::string("--radiosity-frames -1"),
          std::string("--radiosity-frames 2000")}) {
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
