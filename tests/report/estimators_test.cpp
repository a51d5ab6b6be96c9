// The report's comparison of every AO estimator: the frame-to-frame change
// against a hand computation and against the same measure computed here from
// frames this test renders and reads back itself; a tiny run with all six
// estimators, the slice ones at two costs; its figures and summary sections.
#include "deepgi/context.hpp"
#include "deepgi/report.hpp"
#include "deepgi/report_estimators.hpp"
#include "deepgi/shader_loader.hpp"
#include "support/process.hpp"
#include "support/skip.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using deepgi::FloatImage;
namespace report = deepgi::report;

namespace {

FloatImage image(int width, int height, int channels, std::vector<float> pixels) {
    return {width, height, channels, std::move(pixels)};
}

// Header and rows of a CSV file without quoted fields, as column -> field.
std::vector<std::map<std::string, std::string>> read_plain_csv(const fs::path& path) {
    std::istringstream in(spiral::test::read_file(path));
    auto split = [](const std::string& line) {
        std::vector<std::string> fields(1);
        for (char c : line) {
            if (c == ',')
                fields.emplace_back();
            else
                fields.back() += c;
        }
        return fields;
    };
    std::string line;
    std::vector<std::map<std::string, std::string>> rows;
    if (!std::getline(in, line)) return rows;
    const auto header = split(line);
    while (std::getline(in, line)) {
        // report.csv's device column is quoted and holds a comma: read it as
        // one field.
        std::string cleaned;
        bool quoted = false;
        for (char c : line) {
            if (c == '"')
                quoted = !quoted;
            else if (!(quoted && c == ','))
                cleaned += c;
        }
        const auto fields = split(cleaned);
        REQUIRE(fields.size() == header.size());
        std::map<std::string, std::string> row;
        for (std::size_t i = 0; i < header.size(); ++i) row[header[i]] = fields[i];
        rows.push_back(row);
    }
    return rows;
}

// The measure as docs/report.md defines it, written again here: the mean of
// |AV_t(p) - AV_t-1(q)| over viewport pixels with a surface, q = floor(p +
// 1/2 - motion), kept where q lies in the image and its depth is within 5% of
// p's; AV the blurred AO clamped to [0, 1].
struct Sums {
    double sum = 0.0;
    long long pixels = 0;
};
void add_change(const std::vector<float>& before_av, const std::vector<float>& before_depth,
                const std::vector<float>& av, const std::vector<float>& depth,
                const std::vector<float>& motion, int width, int height, int guard, Sums& sums) {
    for (int y = guard; y < height - guard; ++y) {
        for (int x = guard; x < width - guard; ++x) {
            const std::size_t i = std::size_t(y) * width + x;
            if (!(depth[i] > 0.0f)) continue;
            const double px = x + 0.5 - motion[3 * i];
            const double py = y + 0.5 - motion[3 * i + 1];
            const int qx = int(std::floor(px)), qy = int(std::floor(py));
            if (qx < 0 || qy < 0 || qx >= width || qy >= height) continue;
            const std::size_t j = std::size_t(qy) * width + qx;
            if (!(before_depth[j] > 0.0f) ||
                std::abs(before_depth[j] - depth[i]) > 0.05f * depth[i])
                continue;
            const auto clamp01 = [](float v) { return std::min(1.0f, std::max(0.0f, v)); };
            sums.sum += std::abs(double(clamp01(av[i])) - double(clamp01(before_av[j])));
            ++sums.pixels;
        }
    }
}

}  // namespace

TEST_CASE("report estimators: the frame-to-frame change of hand-made frames", "[report]") {
    // 4x3, no guard band; the current frame moved one pixel right, so each
    // pixel's point was one pixel to the left before (motion +1 in x).
    const std::vector<float> before_av = {0.1f, 0.2f, 0.3f, 0.4f,  //
                                          0.5f, 0.6f, 0.7f, 0.8f,  //
                                          0.2f, 0.2f, 0.2f, 0.2f};
    const std::vector<float> now_av = {0.9f, 0.2f, 0.5f, 0.4f,  //
                                       2.0f, 0.6f, 0.6f, 0.7f,  //
                                       0.2f, 0.2f, 0.2f, 0.2f};
    const std::vector<float> before_depth = {1, 1, 1, 1, 1, 1, 1, 1, 0, 1, 1, 1};
    // Pixel (1, 1)'s point was at depth 1 there; it is now at 1.2 (20%
    // farther: another surface, dropped). Row 2's pixel (1, 2) looks at (0, 2),
    // which had no surface. Pixel (3, 2) has no surface now.
    const std::vector<float> now_depth = {1, 1, 1, 1, 1, 1.2f, 1, 1, 1, 1, 1, 0};
    std::vector<float> motion(12 * 3, 0.0f);
    for (int i = 0; i < 12; ++i) motion[3 * i] = 1.0f;
    report::ChangeFrame before{image(4, 3, 1, before_av), image(4, 3, 1, before_depth),
                               image(4, 3, 3, motion)};
    report::ChangeFrame now{image(4, 3, 1, now_av), image(4, 3, 1, now_depth),
                            image(4, 3, 3, motion)};
    // Counted by hand: x = 0 looks off the image (q.x = -1); kept: (1,0):
    // |0.2-0.1|, (2,0): |0.5-0.2|, (3,0): |0.4-0.3|, (2,1): |0.6-0.6|,
    // (3,1): |0.7-0.7|, (2,2): |0.2-0.2|. The clamping of visibility happens
    // when frames are read (read_change_frame), not here: (0, 1)'s 2.0 is off
    // the image anyway.
    const report::ChangeSum change = report::frame_change(before, now, 0);
    CHECK(change.pixels == 6);
    CHECK(change.sum == Approx(0.1 + 0.3 + 0.1).epsilon(1e-6));
    CHECK(change.mean() == Approx(0.5 / 6).epsilon(1e-6));
    // A guard band of one pixel leaves the middle row's inner pixels only.
    const report::ChangeSum inner = report::frame_change(before, now, 1);
    CHECK(inner.pixels == 1);  // (2, 1); (1, 1) is another surface
    CHECK(inner.sum == Approx(0.0).margin(1e-7));
    CHECK(std::isnan(report::ChangeSum{}.mean()));
}

TEST_CASE(
    "report estimators: the measured change equals the same measure of frames read back "
    "here",
    "[report][gl]") {
    deepgi::HeadlessContext context;
    const deepgi::Scene scene = deepgi::load_scene("cornell");
    REQUIRE(scene.camera_path.keys.size() >= 2);
    deepgi::RenderSettings settings;
    settings.width = 96;
    settings.height = 54;
    settings.ao.method = deepgi::AoMethod::gtao;
    const deepgi::ShaderLoader loader = deepgi::ShaderLoader::from_build_configuration();
    constexpr int frames = 6;

    deepgi::Renderer measured(scene, settings, loader);
    const report::FlickerMeasure result = report::measure_flicker(measured, scene, frames);
    REQUIRE(result.has_path);

    // The same sequences on a renderer of their own, read back and measured here.
    deepgi::Renderer renderer(scene, settings, loader);
    const int guard = renderer.layout().guard;
    auto sequence = [&](auto camera) {
        Sums sums;
        std::vector<float> before_av, before_depth;
        for (int k = 1; k <= frames; ++k) {
            renderer.render(camera(k), camera(k + 1),
                            k == 1 ? deepgi::CameraMotion::cut : deepgi::CameraMotion::continuous);
            const FloatImage av = renderer.read_pass_output("ao-blurred");
            const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
            const FloatImage motion = renderer.read_pass_output("gbuffer-motion-layer0");
            REQUIRE(motion.channels == 3);
            if (k >= frames / 2 + 1)
                add_change(before_av, before_depth, av.pixels, depth.pixels, motion.pixels,
                           av.width, av.height, guard, sums);
            before_av = av.pixels;
            before_depth = depth.pixels;
        }
        return sums;
    };
    const Sums still = sequence([&](int) { return scene.default_camera; });
    const Sums path =
        sequence([&](int k) { return deepgi::camera_on_path(scene.camera_path, k - 1); });

    CHECK(result.still.pixels == still.pixels);
    CHECK(result.still.sum == Approx(still.sum).epsilon(1e-9));
    CHECK(result.path.pixels == path.pixels);
    CHECK(result.path.sum == Approx(path.sum).epsilon(1e-9));
    CHECK(still.pixels > 0);
    CHECK(path.pixels > 0);
    // gtao turns its slices every frame, so a still image does change.
    CHECK(result.still.mean() > 0.0);
}

TEST_CASE(
    "report estimators: a tiny run measures all six estimators and their frame-to-frame "
    "change",
    "[report][gl]") {
    deepgi::HeadlessContext context;
    const fs::path output = spiral::test::make_scratch_dir("deepgi-report-estimators");
    report::ReportOptions options;
    options.scenes = {"cornell"};
    options.taps = {4, 8};
    options.patterns = {"optimal", "golden"};
    options.layers = {2};
    options.ao_methods = {deepgi::AoMethod::solid_angle, deepgi::AoMethod::published,
                          deepgi::AoMethod::march,       deepgi::AoMethod::gtao,
                          deepgi::AoMethod::bitmask,     deepgi::AoMethod::spiral_thick};
    options.estimators.slice_costs = {{1, 4}, {2, 8}};
    options.estimators.flicker_frames = 4;
    options.width = 96;
    options.height = 54;
    options.rays = 16;
    options.converged_taps = 64;
    options.warmup = 0;
    options.frames = 1;
    options.repeats = 2;  // the summary's spread needs two
    options.output = output;
    const report::ReportResult result = report::run_report(options);

    // Rows, each twice (the repeats): the solid angle at 2 patterns x 2 tap
    // counts, published and the thick spiral at 2 tap counts, the march
    // once, gtao and bitmask at 2 costs.
    const auto rows = read_plain_csv(output / "report.csv");
    REQUIRE(rows.size() == 26);
    REQUIRE(result.rows.size() == rows.size());
    std::map<std::string, std::vector<std::string>> costs;
    for (const auto& row : rows) {
        INFO(row.at("ao_method") << " " << row.at("pattern") << " " << row.at("taps"));
        const std::string& method = row.at("ao_method");
        const bool slices = method == "gtao" || method == "bitmask";
        CHECK(row.at("ao_slices").empty() == !slices);
        CHECK(row.at("ao_steps").empty() == !slices);
        // Each cost listed once: the first repeat's rows.
        if (row.at("temporal_offset") == "0")
            costs[method].push_back(slices ? row.at("ao_slices") + "x" + row.at("ao_steps")
                                           : row.at("taps"));
        REQUIRE_FALSE(row.at("ref_blur_mae").empty());
        const double mae = std::stod(row.at("ref_blur_mae"));
        CHECK(std::isfinite(mae));
        CHECK(mae >= 0.0);
        CHECK(std::stod(row.at("sao_ms")) > 0.0);
    }
    CHECK(costs["gtao"] == std::vector<std::string>{"1x4", "2x8"});
    CHECK(costs["bitmask"] == std::vector<std::string>{"1x4", "2x8"});
    CHECK(costs["spiral-thick"] == std::vector<std::string>{"4", "8"});
    CHECK(costs["published"] == std::vector<std::string>{"4", "8"});
    CHECK(costs["march"].size() == 1);
    CHECK(costs["solid-angle"].size() == 4);

    // One flicker row per estimator at the image configuration, and the floor.
    const auto flicker = read_plain_csv(output / "flicker.csv");
    REQUIRE(flicker.size() == 7);
    REQUIRE(result.flicker.size() == 7);
    std::vector<std::string> methods;
    for (const auto& row : flicker) {
        INFO(row.at("ao_method") << " " << row.at("role"));
        methods.push_back(row.at("ao_method") + "/" + row.at("role"));
        CHECK(row.at("frames") == "4");
        CHECK(row.at("layers") == "2");
        for (const char* column : {"still_change", "path_change"}) {
            REQUIRE_FALSE(row.at(column).empty());
            const double value = std::stod(row.at(column));
            CHECK(std::isfinite(value));
            CHECK(value >= 0.0);
            CHECK(value <= 1.0);
        }
        CHECK(std::stoll(row.at("still_pixels")) > 0);
        CHECK(std::stoll(row.at("path_pixels")) > 0);
        if (row.at("ao_method") == "gtao" || row.at("ao_method") == "bitmask") {
            // The image cost: the renderer's default 2x8, listed.
            CHECK(row.at("ao_slices") == "2");
            CHECK(row.at("ao_steps") == "8");
        } else {
            CHECK(row.at("ao_slices").empty());
        }
        if (row.at("role") == "floor") CHECK(row.at("taps") == "64");
    }
    CHECK(methods == std::vector<std::string>{"solid-angle/estimator", "published/estimator",
                                              "march/estimator", "gtao/estimator",
                                              "bitmask/estimator", "spiral-thick/estimator",
                                              "solid-angle/floor"});

    // The figures and the summary's sections, where matplotlib is.
    if (fs::exists("/usr/bin/python3") &&
        spiral::test::run_command("/usr/bin/python3 -c 'import matplotlib'").status == 0) {
        const auto plot = spiral::test::run_command("/usr/bin/python3 '" +
                                                    std::string(DEEPGI_PLOT_REPORT_SCRIPT) + "' '" +
                                                    output.string() + "'");
        INFO(plot.err);
        REQUIRE(plot.status == 0);
        CHECK(fs::file_size(output / "estimators_error_vs_ms.png") > 0);
        CHECK(fs::file_size(output / "flicker.png") > 0);
        const std::string summary = spiral::test::read_file(output / "summary.md");
        INFO(summary);
        CHECK(summary.find("## Every estimator at several costs") != std::string::npos);
        CHECK(summary.find("**Spread:**") != std::string::npos);
        CHECK(summary.find("**At equal cost**") != std::string::npos);
        CHECK(summary.find("## Frame-to-frame change") != std::string::npos);
        CHECK(summary.find("| cornell | GTAO 2x8 |") != std::string::npos);
    }
    fs::remove_all(output);
}

TEST_CASE("report estimators: bad slice costs and flicker frames exit 2 with one line",
          "[report]") {
    const fs::path scratch = spiral::test::make_scratch_dir("deepgi-report-estimators-cli");
    const fs::path output = scratch / "out";
    for (const std::string& arguments :
         {std::string("--slice-costs 2"), std::string("--slice-costs 2x"),
          std::string("--slice-costs x8"), std::string("--slice-costs 2x8x1"),
          std::string("--slice-costs 0x8"), std::string("--slice-costs 9x8"),
          std::string("--slice-costs 2x33"), std::string("--slice-costs 2x8,2x8"),
          std::string("--slice-costs -1x4"), std::string("--flicker-frames 3"),
          std::string("--flicker-frames 257"), std::string("--flicker-frames -1")}) {
        const auto run =
            spiral::test::run_command(std::string(DEEPGI_EXECUTABLE) + " report " + arguments +
                                      " --no-plots --output '" + output.string() + "'");
        INFO(arguments << ": " << run.err);
        CHECK(run.status == 2);
        CHECK(spiral::test::count_lines(run.err) == 1);
        CHECK_FALSE(fs::exists(output));
    }
    fs::remove_all(scratch);
}
