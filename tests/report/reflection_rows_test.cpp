// The report's mirror rows (docs/report.md, "Mirror reflections"): a tiny
// run on gallery (a mirror floor) and ref-slab (no mirror) gives one row per
// layer count and step count for gallery and none for ref-slab; the shares
// lie in [0, 1] and sum to 1; and the same-surface share of one row equals a
// count made here from one render's read-back hit texels and the reference's
// own images, with code of its own.
#include "deepgi/context.hpp"
#include "deepgi/reference.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/report.hpp"
#include "support/process.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
namespace report = deepgi::report;

TEST_CASE("report: mirror rows for scenes with mirrors, shares that add up and agree with a count",
          "[report][gl][reflection]") {
    deepgi::HeadlessContext context;
    const fs::path output = spiral::test::make_scratch_dir("deepgi-report-reflection-test");
    report::ReportOptions options;
    options.scenes = {"ref-slab", "gallery"};
    options.taps = {4};
    options.patterns = {"optimal"};
    options.layers = {1, 2};
    options.ao_methods = {deepgi::AoMethod::solid_angle};
    options.width = 96;
    options.height = 54;
    options.rays = 16;
    options.converged_taps = 8;
    options.warmup = 1;
    options.frames = 1;
    options.stability = false;
    options.float_max_n = 0;
    options.reflections.steps = {8, 32};
    options.reflections.frames = 3;
    options.output = output;
    const report::ReportResult result = report::run_report(options);

    // Two layer counts x two step counts, all gallery's.
    REQUIRE(result.reflections.size() == 4);
    std::set<std::string> configurations;
    for (const report::ReflectionRow& row : result.reflections) {
        INFO(row.layers << " layers, " << row.steps << " steps");
        CHECK(row.scene == "gallery");
        CHECK(row.frames == 3);
        configurations.insert(std::to_string(row.layers) + "/" + std::to_string(row.steps));
        CHECK(row.mirror_pixels > 500);
        for (double share :
             {row.same_surface, row.renderer_missed, row.other_surface, row.renderer_only}) {
            CHECK(share >= 0.0);
            CHECK(share <= 1.0);
        }
        // Each share is a count over mirror_pixels; together they cover them.
        const double sum =
            row.same_surface + row.renderer_missed + row.other_surface + row.renderer_only;
        CHECK(sum == Approx(1.0).margin(1e-12));
        for (double share :
             {row.same_surface, row.renderer_missed, row.other_surface, row.renderer_only})
            CHECK(std::abs(share * double(row.mirror_pixels) -
                           std::round(share * double(row.mirror_pixels))) < 1e-6);
        // A floor mirror's reflected rays rise away from it and gallery has
        // no other mirror: none meets one.
        CHECK(row.meets_mirror == 0.0);
        CHECK(std::isnan(row.meets_mirror_rel_mae));
        CHECK(std::isfinite(row.rel_mae));
        CHECK(row.rel_mae >= 0.0);
        CHECK(std::isfinite(row.rel_bias));
        CHECK(row.reflection_ms > 0.0);
        CHECK(row.device == deepgi::query_context_info().renderer);
    }
    CHECK(configurations == std::set<std::string>{"1/8", "1/32", "2/8", "2/32"});

    // The CSV holds the same rows, and ref-slab none.
    std::istringstream csv(spiral::test::read_file(output / "reflections.csv"));
    std::string line;
    REQUIRE(std::getline(csv, line));
    CHECK(line.rfind("scene,layers,steps,frames,device,mirror_pixels,same_surface,", 0) == 0);
    int csv_rows = 0;
    while (std::getline(csv, line)) {
        ++csv_rows;
        CHECK(line.rfind("gallery,", 0) == 0);
    }
    CHECK(csv_rows == 4);

    // An independent count for the two-layer, 32-step row: render the same
    // frames alone, read back the hit texels, and map each to the surface
    // the reference's camera ray stores in the layer hit.
    const report::ReflectionRow* checked = nullptr;
    for (const report::ReflectionRow& row : result.reflections)
        if (row.layers == 2 && row.steps == 32) checked = &row;
    REQUIRE(checked != nullptr);
    const deepgi::Scene scene = deepgi::load_scene("gallery");
    deepgi::RenderSettings settings;
    settings.width = options.width;
    settings.height = options.height;
    settings.radiosity.rho_prop = 0.0f;  // as the report renders; the march does not read it
    settings.reflection.layers = 2;
    settings.reflection.steps = 32;
    deepgi::Renderer renderer(scene, settings, deepgi::ShaderLoader::from_build_configuration());
    for (int frame = 0; frame < options.reflections.frames; ++frame)
        renderer.render(scene.default_camera,
                        frame == 0 ? deepgi::CameraMotion::cut : deepgi::CameraMotion::continuous);
    const deepgi::FloatImage hit = renderer.read_pass_output("reflection-hit");
    const deepgi::FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
    deepgi::ReferenceSettings traced;
    traced.render = settings;
    traced.ambient_visibility = false;
    traced.reflections = true;
    traced.irradiance_rays.min_rays = traced.irradiance_rays.max_rays = 16;
    const deepgi::RayScene rays(scene);
    const deepgi::ReferenceImages truth =
        deepgi::render_reference(rays, scene.default_camera, traced);
    const int guard = deepgi::frame_layout(settings).guard;
    REQUIRE(hit.channels >= 3);
    const std::size_t k = std::size_t(hit.channels);
    long long compared = 0, agreeing = 0;
    for (int y = guard; y < hit.height - guard; ++y)
        for (int x = guard; x < hit.width - guard; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(hit.width) + std::size_t(x);
            const float raster = depth.pixels[i], ray = truth.depth_layer0.pixels[i];
            const bool depths_agree =
                raster > 0.0f && ray > 0.0f && std::abs(raster - ray) <= 1e-3f * ray;
            const bool mirror_both =
                truth.surface_layers.pixels[3 * i + 2] == 1.0f && hit.pixels[k * i + 2] > -2.0f;
            if (!depths_agree || !mirror_both) continue;
            ++compared;
            const float layer = hit.pixels[k * i + 2];
            int renderer_surface = -1;
            if (layer >= 0.0f) {
                // The hit texel's centre is (texel + 0.5): truncation finds the texel.
                const auto tx = std::size_t(hit.pixels[k * i]);
                const auto ty = std::size_t(hit.pixels[k * i + 1]);
                const std::size_t j = ty * std::size_t(hit.width) + tx;
                renderer_surface =
                    int(truth.surface_layers.pixels[3 * j + (layer >= 1.0f ? 1 : 0)]);
            }
            agreeing += renderer_surface == int(truth.reflection_hit.pixels[3 * i]);
        }
    INFO("compared " << compared << ", agreeing " << agreeing);
    CHECK(compared == checked->mirror_pixels);
    CHECK(double(agreeing) / double(compared) == Approx(checked->same_surface).margin(1e-12));
    fs::remove_all(output);
}

TEST_CASE("report: bad mirror-row options exit 2 with one line and leave no output", "[report]") {
    const fs::path scratch = spiral::test::make_scratch_dir("deepgi-report-reflection-cli");
    const fs::path output = scratch / "out";
    for (const std::string arguments :
         {"--reflection-steps 0", "--reflection-steps 16,x", "--reflection-steps 2000",
          "--reflection-frames 0", "--reflection-frames 1001"}) {
        const auto run = spiral::test::run_command(std::string(DEEPGI_EXECUTABLE) + " report " +
                                                   arguments + " --scenes gallery --no-plots " +
                                                   "--output '" + output.string() + "'");
        INFO(arguments << ": " << run.err);
        CHECK(run.status == 2);
        CHECK(spiral::test::count_lines(run.err) == 1);
        CHECK_FALSE(fs::exists(output));
    }
    fs::remove_all(scratch);
}
