// ao_noise_study: "does the optimum pay?" Per-pixel noise of the raw deep SAO
// output on the cornell floor along the left (red) wall, for the discrepancy-optimal
// tau, tau = 1 and a golden-angle spiral.
//
// The noise of a pixel is the standard deviation of its raw visibility over
// the per-pixel rotation phi: the pattern is run --rotations times, turned by
// 2*pi*k/rotations each time (the same as shifting every pixel's phi), and
// the spread at each pixel is what the bilateral blur has to remove. The table
// gives the mean of that standard deviation over the region, and the region's
// mean visibility for orientation.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/renderer.hpp"
#include "study_headers.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>

namespace {

struct Pattern {
    std::string name;
    int turns = 0;  // 0: not an integer spiral
    std::vector<spiral::codegen::Tap> taps;
};

struct Region {
    std::vector<std::size_t> pixels;  // indices into the internal-size image
};

// Floor pixels (camera-space normal close to +y, since the default camera is
// level) whose world position lies in the box, from the renderer's own
// depth pyramid and normals.
Region select_region(const deepgi::Renderer& renderer, const deepgi::Scene& scene,
                     glm::vec2 x_range, glm::vec2 z_range) {
    const deepgi::FloatImage depth = renderer.read_pass_output("depth_pyramid-level0");
    const deepgi::FloatImage normal = renderer.read_pass_output("gbuffer-normal-layer0");
    const glm::mat4 projection =
        deepgi::guard_band_projection(scene.default_camera, renderer.settings());
    const glm::mat4 camera_to_world =
        glm::inverse(deepgi::camera_view_matrix(scene.default_camera));
    Region region;
    for (int y = 0; y < depth.height; ++y) {
        for (int x = 0; x < depth.width; ++x) {
            const float z = depth.at(x, y, 0);
            if (z <= 0.0f || normal.at(x, y, 1) < 0.99f) continue;
            const float ndc_x = (float(x) + 0.5f) / float(depth.width) * 2.0f - 1.0f;
            const float ndc_y = (float(y) + 0.5f) / float(depth.height) * 2.0f - 1.0f;
            const glm::vec4 camera(ndc_x / projection[0][0] * z, ndc_y / projection[1][1] * z, -z,
                                   1.0f);
            const glm::vec3 world = glm::vec3(camera_to_world * camera);
            if (world.x >= x_range.x && world.x <= x_range.y && world.z >= z_range.x &&
                world.z <= z_range.y) {
                region.pixels.push_back(std::size_t(y) * std::size_t(depth.width) + std::size_t(x));
            }
        }
    }
    return region;
}

}  // namespace

int main(int argc, char** argv) {
    std::string size = "640x360";
    std::vector<int> tap_counts = {8, 11, 16, 32};
    int rotations = 16;
    std::vector<float> x_range = {-0.97f, -0.72f};
    std::vector<float> z_range = {0.1f, 0.9f};
    CLI::App app{
        "ao_noise_study: per-pixel noise of raw deep SAO for three tap patterns (cornell)"};
    app.add_option("--size", size, "WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--taps", tap_counts, "Tap counts")->capture_default_str();
    app.add_option("--rotations", rotations, "Turns of each pattern the spread is taken over")
        ->capture_default_str();
    app.add_option("--region-x", x_range, "World x range of the floor region (m)")
        ->expected(2)
        ->capture_default_str();
    app.add_option("--region-z", z_range, "World z range of the floor region (m)")
        ->expected(2)
        ->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    try {
        const deepgi::ImageSize image = deepgi::parse_size("--size", size);
        if (rotations < 2) throw deepgi::InputError("--rotations must be at least 2");
        for (int n : tap_counts) {
            if (n < 1 || n > 1024)
                throw deepgi::InputError(fmt::format("--taps {} is out of range (1 to 1024)", n));
        }
        deepgi::RenderSettings settings;
        settings.width = image.width;
        settings.height = image.height;
        settings.shadow_map_size = 256;
        // The spiral gather: the march casts rays of its own, whatever the pattern.
        settings.ao.method = deepgi::AoMethod::solid_angle;
        const deepgi::Scene scene = deepgi::make_builtin_scene("cornell");

        deepgi::HeadlessContext context;
        deepgi::study::ScratchFolder headers;
        const deepgi::ShaderLoader loader = deepgi::study::loader_with_override(headers.path());

        fmt::print(
            "| N | pattern | tau | mean per-pixel std of raw AV | mean AV "
            "|\n|--:|:--|--:|--:|--:|\n");
        std::size_t region_size = 0;
        for (int n : tap_counts) {
            const int optimal_tau = spiral::search(n).tau;
            const std::vector<Pattern> patterns = {
                {"optimal tau", optimal_tau, spiral::codegen::spiral_taps(n, optimal_tau)},
                {"tau = 1", 1, spiral::codegen::spiral_taps(n, 1)},
                {"golden angle", 0, deepgi::study::golden_angle_taps(n)},
            };
            for (const Pattern& candidate : patterns) {
                std::vector<double> sum;
                std::vector<double> sum_squares;
                Region region;
                for (int k = 0; k < rotations; ++k) {
                    const double turn = 2.0 * 3.141592653589793 * double(k) / double(rotations);
                    spiral::codegen::write_file_atomically(
                        headers.path() / "ao_taps.glsl",
                        deepgi::study::format_ao_header(
                            deepgi::study::rotated(candidate.taps, turn), candidate.turns,
                            candidate.name));
                    deepgi::Renderer renderer(scene, settings, loader);
                    renderer.render(scene.default_camera);
                    if (k == 0) {
                        region = select_region(renderer, scene, {x_range[0], x_range[1]},
                                               {z_range[0], z_range[1]});
                        if (region.pixels.empty())
                            throw deepgi::InputError(
                                "the region holds no floor pixels at this size");
                        sum.assign(region.pixels.size(), 0.0);
                        sum_squares.assign(region.pixels.size(), 0.0);
                    }
                    const deepgi::FloatImage raw = renderer.read_pass_output("ao-raw");
                    for (std::size_t i = 0; i < region.pixels.size(); ++i) {
                        const double value = raw.pixels[region.pixels[i]];
                        sum[i] += value;
                        sum_squares[i] += value * value;
                    }
                }
                double total_std = 0.0;
                double total_mean = 0.0;
                for (std::size_t i = 0; i < sum.size(); ++i) {
                    const double mean = sum[i] / rotations;
                    total_mean += mean;
                    total_std += std::sqrt(std::max(0.0, sum_squares[i] / rotations - mean * mean));
                }
                region_size = sum.size();
                fmt::print("| {} | {} | {} | {:.4f} | {:.3f} |\n", n, candidate.name,
                           candidate.turns ? fmt::format("{}", candidate.turns) : "-",
                           total_std / double(sum.size()), total_mean / double(sum.size()));
                std::fflush(stdout);
            }
        }
        fmt::print(
            "\ncornell {}x{}, floor x in [{}, {}] m, z in [{}, {}] m ({} pixels), {} rotations per "
            "pattern, "
            "default AO settings, solid-angle estimator\n",
            settings.width, settings.height, x_range[0], x_range[1], z_range[0], z_range[1],
            region_size, rotations);
        return 0;
    } catch (const deepgi::InputError& error) {
        fmt::print(stderr, "ao_noise_study: error: {}\n", error.what());
        return 2;
    } catch (const std::exception& error) {
        fmt::print(stderr, "ao_noise_study: error: {}\n", error.what());
        return 1;
    }
}
