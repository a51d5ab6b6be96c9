// `deepgi reference`: ray-traces the ambient visibility that deep SAO
// estimates and the one-bounce irradiance that deep radiosity gathers, on the same guard-banded
// pixel grid as `deepgi --headless
// --dump`, and writes it as PFM images (docs/reference.md).
#include "reference_command.hpp"

#include "command_line.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/settings.hpp"
#include "deepgi/reference.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <spiral/fileio.hpp>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace fs = std::filesystem;

namespace deepgi_app {
namespace {

struct ReferenceOptions {
    std::string scene = "cornell";
    std::string size = "1280x720";
    std::string output;
    int rays = 65536;
    int min_rays = 1024;
    double target_error = 0.004;
    std::uint64_t seed = 1;
    int threads = 0;
    float radius = deepgi::RenderSettings{}.ao.radius;
    float guard_band = deepgi::RenderSettings{}.guard_band_fraction;
    float min_separation = deepgi::RenderSettings{}.min_separation;
    bool no_ao = false;
    bool no_irradiance = false;
    float radiosity_radius = deepgi::RenderSettings{}.radiosity.radius;
    int irradiance_rays = 16384;
    int irradiance_min_rays = 1024;
    int irradiance_ceiling_rays = 65536;
    double irradiance_target_error = 0.01;
};

// The row of a renderer setting the reference shares (settings.hpp).
const deepgi::NumericSetting& row(std::string_view name) {
    return *deepgi::find_numeric_setting(name);
}

// "<the row's help> (<its limits>), as deepgi --NAME"
std::string row_help(std::string_view name) {
    return fmt::format("{} ({}), as deepgi --{}", row(name).help,
                       deepgi::describe_limits(row(name)), name);
}

int run(const ReferenceOptions& options) {
    deepgi::ReferenceSettings settings;
    const deepgi::ImageSize size = deepgi::parse_size("--size", options.size);
    settings.render.width = size.width;
    settings.render.height = size.height;
    if (options.output.empty()) throw deepgi::InputError("reference needs --output DIR");
    if (options.rays < 1) throw deepgi::InputError("--rays must be at least 1");
    if (options.threads < 0 || options.threads > 1024)
        throw deepgi::InputError(
            fmt::format("--threads {} must lie in [0, 1024] (0: all)", options.threads));
    // The renderer's settings the reference shares, checked by their rows.
    deepgi::check_setting(row("ao-radius"), options.radius);
    deepgi::check_setting(row("guard-band"), options.guard_band);
    deepgi::check_setting(row("min-separation"), options.min_separation);
    deepgi::check_setting(row("radiosity-radius"), options.radiosity_radius);
    if (!(options.target_error >= 0.0)) throw deepgi::InputError("--target-error must be >= 0");
    if (options.irradiance_rays < 1)
        throw deepgi::InputError("--irradiance-rays must be at least 1");
    if (options.irradiance_ceiling_rays < 1)
        throw deepgi::InputError("--irradiance-ceiling-rays must be at least 1");
    if (!(options.irradiance_target_error >= 0.0))
        throw deepgi::InputError("--irradiance-target-error must be >= 0");
    if (options.no_ao && options.no_irradiance)
        throw deepgi::InputError("--no-ao and --no-irradiance leave nothing to trace");
    const fs::path output = options.output;
    // Written as one set, like --dump: checked before any ray is traced, the
    // images appear together or not at all (a previous set of PFM images is
    // replaced whole; a folder holding anything else is refused).
    spiral::fileio::check_directory_target(output, ".pfm");

    settings.render.guard_band_fraction = options.guard_band;
    settings.render.min_separation = options.min_separation;
    settings.render.ao.radius = options.radius;
    settings.rays.max_rays = options.rays;
    settings.rays.min_rays = std::min(options.min_rays, options.rays);
    settings.rays.target_error = options.target_error;
    settings.ambient_visibility = !options.no_ao;
    settings.irradiance = !options.no_irradiance;
    settings.radiosity_radius = options.radiosity_radius;
    settings.irradiance_rays.max_rays = options.irradiance_rays;
    settings.irradiance_rays.min_rays =
        std::min(options.irradiance_min_rays, options.irradiance_rays);
    settings.irradiance_rays.ceiling_max_rays = options.irradiance_ceiling_rays;
    settings.irradiance_rays.target_relative_error = options.irradiance_target_error;
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

    spiral::fileio::AtomicDirectory set(output, ".pfm");
    auto write = [&](const char* name, const deepgi::FloatImage& image) {
        const std::vector<std::uint8_t> bytes = deepgi::encode_pfm(image);
        set.write_file(name, bytes.data(), bytes.size());
    };
    write("reference-depth-layer0.pfm", images.depth_layer0);
    write("reference-depth-layer1.pfm", images.depth_layer1);
    if (settings.ambient_visibility) {
        write("reference-ao-visibility.pfm", images.ambient_visibility);
        write("reference-ao-hit-visibility.pfm", images.hit_visibility);
        write("reference-ao-occlusion-split.pfm", images.occlusion_split);
        write("reference-ao-standard-error.pfm", images.standard_error);
        write("reference-ao-rays.pfm", images.rays);
    }
    if (settings.irradiance) {
        write("reference-irradiance.pfm", images.irradiance);
        write("reference-irradiance-standard-error.pfm", images.irradiance_standard_error);
        write("reference-irradiance-rays.pfm", images.irradiance_rays);
        write("reference-direct-radiance.pfm", images.direct_radiance);
    }
    set.commit();

    if (settings.ambient_visibility) {
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
            "reference: {} pixels on surfaces, {:.0f} rays per pixel on average, standard error "
            "max {:.4f} ({} pixels at or above 0.005), {:.1f} s\n",
            surface, surface ? ray_total / double(surface) : 0.0, max_error, above, seconds);
    }
    if (settings.irradiance) {
        // Errors relative to each pixel's E, over pixels that receive light;
        // the largest channel's standard error per pixel against 0.005.
        double ray_total = 0.0, mean_e = 0.0, mean_error = 0.0, max_relative = 0.0;
        long long surface = 0, lit = 0, below = 0;
        std::vector<double> errors;
        for (std::size_t i = 0; i < images.irradiance_rays.pixels.size(); ++i) {
            if (images.depth_layer0.pixels[i] <= 0.0f) continue;
            ++surface;
            ray_total += images.irradiance_rays.pixels[i];
            double e = 0.0, error = 0.0;
            for (int c = 0; c < 3; ++c) {
                e = std::max(e, double(images.irradiance.pixels[3 * i + c]));
                error = std::max(error, double(images.irradiance_standard_error.pixels[3 * i + c]));
            }
            mean_e += e;
            mean_error += error;
            errors.push_back(error);
            if (error < 0.005) ++below;
            if (e > 0.0) {
                ++lit;
                max_relative = std::max(max_relative, error / e);
            }
        }
        const double n = double(std::max(surface, 1LL));
        double median = 0.0;
        if (!errors.empty()) {
            const auto middle = errors.begin() + std::ptrdiff_t(errors.size() / 2);
            std::nth_element(errors.begin(), middle, errors.end());
            median = *middle;
        }
        fmt::print(
            "reference irradiance: {} pixels on surfaces, {:.0f} rays per pixel on average, mean "
            "E (largest channel) {:.4g}, mean standard error {:.4g}, median {:.4g}, {:.1f}% of "
            "pixels below 0.005, largest relative standard error {:.4f} over {} pixels with "
            "E > 0, {:.1f} s in all\n",
            surface, ray_total / n, mean_e / n, mean_error / n, median, 100.0 * double(below) / n,
            max_relative, lit, seconds);
    }
    return 0;
}

}  // namespace

int run_reference_command(int argc, char** argv) {
    ReferenceOptions options;
    CLI::App app{
        "deepgi reference: ray-traced ambient visibility and one-bounce irradiance on layer 0's "
        "pixel grid"};
    app.add_option("--scene", options.scene, "cornell, atrium, warehouse, or a .gltf/.glb file");
    app.add_option("--size", options.size, "Viewport size WIDTHxHEIGHT (guard band added)");
    app.add_option("--output", options.output, "Directory for the PFM images");
    app.add_option("--rays", options.rays, "Most rays per pixel");
    app.add_option("--min-rays", options.min_rays, "Fewest rays per pixel");
    app.add_option("--target-error", options.target_error,
                   "Stop adding rays once the standard error (times 1.3) is below this");
    app.add_option("--seed", options.seed, "Random seed (same seed, same images)");
    app.add_option("--threads", options.threads, "Worker threads (0: all)");
    app.add_option("--ao-radius", options.radius, row_help("ao-radius"));
    app.add_option("--guard-band", options.guard_band, row_help("guard-band"));
    app.add_option("--min-separation", options.min_separation, row_help("min-separation"));
    app.add_flag("--no-ao", options.no_ao, "Do not trace ambient visibility");
    app.add_flag("--no-irradiance", options.no_irradiance, "Do not trace one-bounce irradiance");
    app.add_option("--radiosity-radius", options.radiosity_radius, row_help("radiosity-radius"));
    app.add_option("--irradiance-rays", options.irradiance_rays,
                   "Most irradiance rays per pixel (cosine directions and emitter shadow rays)");
    app.add_option("--irradiance-min-rays", options.irradiance_min_rays,
                   "Fewest irradiance rays per pixel");
    app.add_option("--irradiance-ceiling-rays", options.irradiance_ceiling_rays,
                   "Most irradiance rays per pixel whose standard error is still at or above "
                   "0.005 after --irradiance-rays");
    app.add_option("--irradiance-target-error", options.irradiance_target_error,
                   "Stop adding irradiance rays once every channel's standard error (times "
                   "1.3) is below this fraction of E, or 0.002, and below 0.005");
    if (const auto status = parse_command_line(app, argc - 1, argv + 1, "deepgi reference"))
        return *status;
    return run_reporting_errors("deepgi reference", [&] { return run(options); });
}

}  // namespace deepgi_app
