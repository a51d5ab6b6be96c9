// `deepgi reference`: ray-traces the ambient visibility that deep SAO
// estimates, on the same guard-banded pixel grid as `deepgi --headless
// --dump`, and writes it as PFM images (docs/reference.md).
#include "reference_command.hpp"

#include "deepgi/errors.hpp"
#include "deepgi/reference.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <regex>

namespace fs = std::filesystem;

namespace deepgi_app {
namespace {

constexpr int exit_bad_input = 2;

struct ReferenceOptions {
    std::string scene = "cornell";
    std::string size = "1280x720";
    std::string output;
    int rays = 65536;
    int min_rays = 1024;
    double target_error = 0.004;
    std::uint64_t seed = 1;
    int threads = 0;
    float radius = 0.5f;
    float guard_band = 0.1f;
    float min_separation = 0.5f;
};

void parse_size(const std::string& text, deepgi::RenderSettings& settings) {
    static const std::regex pattern(R"(^(\d{1,5})x(\d{1,5})$)");
    std::smatch match;
    if (!std::regex_match(text, match, pattern))
        throw deepgi::InputError(fmt::format("--size '{}' is not WIDTHxHEIGHT", text));
    settings.width = std::stoi(match[1].str());
    settings.height = std::stoi(match[2].str());
    if (settings.width < 1 || settings.height < 1 || settings.width > 16384 ||
        settings.height > 16384)
        throw deepgi::InputError(fmt::format("--size {} is out of range (1 to 16384)", text));
}

int run(const ReferenceOptions& options) {
    deepgi::ReferenceSettings settings;
    parse_size(options.size, settings.render);
    if (options.output.empty()) throw deepgi::InputError("reference needs --output DIR");
    if (options.rays < 1) throw deepgi::InputError("--rays must be at least 1");
    if (!(options.radius > 0.0f) || !std::isfinite(options.radius))
        throw deepgi::InputError("--ao-radius must be a finite number of metres > 0");
    if (!(options.guard_band >= 0.0f && options.guard_band <= 1.0f))
        throw deepgi::InputError("--guard-band must be in [0, 1]");
    if (!(options.min_separation >= 0.0f) || !std::isfinite(options.min_separation))
        throw deepgi::InputError("--min-separation must be a finite number of metres >= 0");
    if (!(options.target_error >= 0.0)) throw deepgi::InputError("--target-error must be >= 0");
    const fs::path output = options.output;
    if (fs::exists(output) && !fs::is_directory(output))
        throw deepgi::InputError(fmt::format("--output '{}' is not a directory", output.string()));
    const fs::path parent = output.has_parent_path() ? output.parent_path() : fs::path(".");
    if (!fs::is_directory(parent))
        throw deepgi::InputError(fmt::format("--output '{}': directory '{}' does not exist",
                                             output.string(), parent.string()));

    settings.render.guard_band_fraction = options.guard_band;
    settings.render.min_separation = options.min_separation;
    settings.render.ao.radius = options.radius;
    settings.rays.max_rays = options.rays;
    settings.rays.min_rays = std::min(options.min_rays, options.rays);
    settings.rays.target_error = options.target_error;
    settings.seed = options.seed;
    settings.threads = options.threads;
    // A progress bar only where someone watches; logs stay clean.
    if (isatty(fileno(stderr))) {
        settings.progress = [](long long done, long long total) {
            const int width = 40;
            const int filled = total > 0 ? int(width * done / total) : width;
            fmt::print(stderr, "\r[{:<{}}] {:3d}%", std::string(filled, '#'), width,
                       total > 0 ? int(100 * done / total) : 100);
            if (done >= total) fmt::print(stderr, "\n");
            std::fflush(stderr);
        };
    }

    const deepgi::Scene scene = deepgi::load_scene(options.scene);
    const auto start = std::chrono::steady_clock::now();
    const deepgi::RayScene rays(scene);
    const deepgi::ReferenceImages images =
        deepgi::render_reference(rays, scene.default_camera, settings);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    fs::create_directories(output);
    deepgi::write_pfm(output / "reference-depth-layer0.pfm", images.depth_layer0);
    deepgi::write_pfm(output / "reference-depth-layer1.pfm", images.depth_layer1);
    deepgi::write_pfm(output / "reference-ao-visibility.pfm", images.ambient_visibility);
    deepgi::write_pfm(output / "reference-ao-hit-visibility.pfm", images.hit_visibility);
    deepgi::write_pfm(output / "reference-ao-occlusion-split.pfm", images.occlusion_split);
    deepgi::write_pfm(output / "reference-ao-standard-error.pfm", images.standard_error);
    deepgi::write_pfm(output / "reference-ao-rays.pfm", images.rays);

    double max_error = 0.0, ray_total = 0.0;
    long long surface = 0, above = 0;
    for (std::size_t i = 0; i < images.standard_error.pixels.size(); ++i) {
        if (images.depth_layer0.pixels[i] <= 0.0f) continue;
        ++surface;
        max_error = std::max(max_error, double(images.standard_error.pixels[i]));
        ray_total += images.rays.pixels[i];
        if (images.standard_error.pixels[i] >= 0.005f) ++above;
    }
    fmt::print(
        "reference: {} pixels on surfaces, {:.0f} rays per pixel on average, standard error max "
        "{:.4f} ({} pixels at or above 0.005), {:.1f} s\n",
        surface, surface ? ray_total / double(surface) : 0.0, max_error, above, seconds);
    return 0;
}

}  // namespace

int run_reference_command(int argc, char** argv) {
    ReferenceOptions options;
    CLI::App app{"deepgi reference: ray-traced ambient visibility on layer 0's pixel grid"};
    app.add_option("--scene", options.scene, "cornell, atrium, warehouse, or a .gltf/.glb file");
    app.add_option("--size", options.size, "Viewport size WIDTHxHEIGHT (guard band added)");
    app.add_option("--output", options.output, "Directory for the PFM images");
    app.add_option("--rays", options.rays, "Most rays per pixel");
    app.add_option("--min-rays", options.min_rays, "Fewest rays per pixel");
    app.add_option("--target-error", options.target_error,
                   "Stop adding rays once the standard error is below this");
    app.add_option("--seed", options.seed, "Random seed (same seed, same images)");
    app.add_option("--threads", options.threads, "Worker threads (0: all)");
    app.add_option("--ao-radius", options.radius, "AO radius r (m), as deepgi --ao-radius");
    app.add_option("--guard-band", options.guard_band, "Guard band, fraction of the height");
    app.add_option("--min-separation", options.min_separation, "Layer-1 separation dz (m)");
    try {
        app.parse(argc - 1, argv + 1);
    } catch (const CLI::CallForHelp&) {
        fmt::print("{}", app.help());
        return 0;
    } catch (const CLI::ParseError& error) {
        std::string message = error.what();
        std::replace(message.begin(), message.end(), '\n', ' ');
        fmt::print(stderr, "deepgi reference: error: {}\n", message);
        return exit_bad_input;
    }
    try {
        return run(options);
    } catch (const deepgi::InputError& error) {
        fmt::print(stderr, "deepgi reference: error: {}\n", error.what());
        return exit_bad_input;
    } catch (const std::exception& error) {
        fmt::print(stderr, "deepgi reference: error: {}\n", error.what());
        return 1;
    }
}

}  // namespace deepgi_app
