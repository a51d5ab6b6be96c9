// `deepgi reference`: ray-traces the ambient visibility that deep SAO
// estimates and the one-bounce irradiance that deep radiosity gathers, on the same guard-banded
// pixel grid as `deepgi --headless
// --dump`, and writes it as PFM images (docs/reference.md).
#include "reference_command.hpp"

#include "command_line.hpp"
#include "help_formatter.hpp"
#include "reference_preview.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/settings.hpp"
#include "deepgi/reference.hpp"
#include "deepgi/renderer.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <spiral/fileio.hpp>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
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
    // Lengths as typed: a number or "auto", resolved against the scene as
    // deepgi resolves them, so both measure the same radii by default.
    std::string radius = "auto";
    float guard_band = deepgi::RenderSettings{}.guard_band_fraction;
    std::string min_separation = "auto";
    bool no_ao = false;
    bool no_irradiance = false;
    bool no_reflections = false;
    float mirror_roughness = deepgi::RenderSettings{}.mirror_roughness;
    std::string radiosity_radius = "auto";
    int irradiance_rays = 16384;
    int irradiance_min_rays = 1024;
    int irradiance_ceiling_rays = 65536;
    double irradiance_target_error = 0.01;
    int bounces = 1;
};

// Diffuse bounces the irradiance may trace: each is one more ray per
// sample, and a few already show how far the renderer's rho_prop reaches.
constexpr int max_bounces = 4;

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
    deepgi::check_setting(row("guard-band"), options.guard_band);
    deepgi::check_setting(row("mirror-roughness"), options.mirror_roughness);
    settings.render.mirror_roughness = options.mirror_roughness;
    row("ao-radius")
        .set(settings.render, deepgi::parse_setting_value(row("ao-radius"), options.radius));
    row("min-separation")
        .set(settings.render,
             deepgi::parse_setting_value(row("min-separation"), options.min_separation));
    row("radiosity-radius")
        .set(settings.render,
             deepgi::parse_setting_value(row("radiosity-radius"), options.radiosity_radius));
    if (!(options.target_error >= 0.0)) throw deepgi::InputError("--target-error must be >= 0");
    if (options.irradiance_rays < 1)
        throw deepgi::InputError("--irradiance-rays must be at least 1");
    if (options.irradiance_ceiling_rays < 1)
        throw deepgi::InputError("--irradiance-ceiling-rays must be at least 1");
    if (!(options.irradiance_target_error >= 0.0))
        throw deepgi::InputError("--irradiance-target-error must be >= 0");
    if (options.bounces < 1 || options.bounces > max_bounces)
        throw deepgi::InputError(
            fmt::format("--bounces {} must lie in [1, {}]", options.bounces, max_bounces));
    if (options.no_ao && options.no_irradiance)
        throw deepgi::InputError("--no-ao and --no-irradiance leave nothing to trace");
    const fs::path output = options.output;
    // Written as one set, like --dump: checked before any ray is traced, the
    // images and their previews appear together or not at all (a previous set
    // of PFM images and PNG previews is replaced whole; a folder holding
    // anything else is refused).
    spiral::fileio::check_directory_target(output, ".pfm .png");

    settings.render.guard_band_fraction = options.guard_band;
    settings.rays.max_rays = options.rays;
    settings.rays.min_rays = std::min(options.min_rays, options.rays);
    settings.rays.target_error = options.target_error;
    settings.ambient_visibility = !options.no_ao;
    settings.irradiance = !options.no_irradiance;
    settings.reflections = !options.no_reflections;
    settings.irradiance_rays.max_rays = options.irradiance_rays;
    settings.irradiance_rays.min_rays =
        std::min(options.irradiance_min_rays, options.irradiance_rays);
    settings.irradiance_rays.ceiling_max_rays = options.irradiance_ceiling_rays;
    settings.irradiance_rays.target_relative_error = options.irradiance_target_error;
    settings.bounces = options.bounces;
    settings.seed = options.seed;
    settings.threads = options.threads;
    // A progress bar only where someone watches; logs stay clean.
    // The library reports the ambient visibility, then the irradiance (each
    // when traced), each ending with done == total.
    auto phases = std::make_shared<std::vector<std::string>>();
    if (isatty(fileno(stderr))) {
        if (!options.no_ao) phases->push_back("ambient visibility");
        if (!options.no_irradiance) phases->push_back("irradiance");
        auto phase = std::make_shared<std::size_t>(0);
        settings.progress = [phases, phase](long long done, long long total) {
            const int width = 40;
            const int filled = total > 0 ? int(width * done / total) : width;
            const std::string& label = *phase < phases->size() ? (*phases)[*phase] : phases->back();
            fmt::print(stderr, "\rdeepgi reference: {:<18} pixels [{:<{}}] {:3d}%", label,
                       std::string(filled, '#'), width, total > 0 ? int(100 * done / total) : 100);
            if (done >= total) {
                fmt::print(stderr, "\n");
                ++*phase;
            }
            std::fflush(stderr);
        };
    }

    const deepgi::Scene scene = deepgi::load_scene(options.scene);
    const deepgi::RayScene rays(scene);
    if (settings.progress && settings.reflections &&
        rays.has_mirrors(settings.render.mirror_roughness)) {
        phases->push_back("reflections");
    }
    const deepgi::RenderSettings given = settings.render;
    settings.render = deepgi::resolve_auto_lengths(settings.render, deepgi::scene_scale(scene));
    settings.radiosity_radius = settings.render.radiosity.radius;
    for (const std::string& line :
         deepgi::describe_auto_lengths(given, settings.render, deepgi::scene_scale(scene)))
        fmt::print("scene scale: {}\n", line);
    const auto start = std::chrono::steady_clock::now();
    const deepgi::ReferenceImages images =
        deepgi::render_reference(rays, scene.default_camera, settings);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    // Every image as PFM with its PNG preview beside it; the whole set is
    // written before any file is committed, so a failure leaves none.
    using deepgi_app::PreviewMapping;
    struct Output {
        const char* name;
        const deepgi::FloatImage* image;
        PreviewMapping preview;
    };
    std::vector<Output> outputs = {
        {"reference-depth-layer0", &images.depth_layer0, PreviewMapping::depth},
        {"reference-depth-layer1", &images.depth_layer1, PreviewMapping::depth}};
    if (settings.ambient_visibility) {
        outputs.insert(
            outputs.end(),
            {{"reference-ao-visibility", &images.ambient_visibility, PreviewMapping::unit},
             {"reference-ao-hit-visibility", &images.hit_visibility, PreviewMapping::unit},
             {"reference-ao-occlusion-split", &images.occlusion_split, PreviewMapping::unit},
             {"reference-ao-standard-error", &images.standard_error, PreviewMapping::normalised},
             {"reference-ao-rays", &images.rays, PreviewMapping::normalised}});
    }
    if (settings.irradiance) {
        outputs.insert(
            outputs.end(),
            {{"reference-irradiance", &images.irradiance, PreviewMapping::irradiance},
             {"reference-irradiance-standard-error", &images.irradiance_standard_error,
              PreviewMapping::normalised},
             {"reference-irradiance-rays", &images.irradiance_rays, PreviewMapping::normalised},
             {"reference-irradiance-layer0", &images.irradiance_layer0, PreviewMapping::irradiance},
             {"reference-irradiance-layer1", &images.irradiance_layer1, PreviewMapping::irradiance},
             {"reference-irradiance-neither", &images.irradiance_neither,
              PreviewMapping::irradiance},
             {"reference-direct-radiance", &images.direct_radiance, PreviewMapping::radiance}});
    }
    // Only for a scene with mirrors: a scene without writes the same set as
    // before reflections were traced.
    if (!images.reflection_radiance.pixels.empty()) {
        outputs.insert(
            outputs.end(),
            {{"reference-reflection-radiance", &images.reflection_radiance,
              PreviewMapping::radiance},
             {"reference-reflection-hit", &images.reflection_hit, PreviewMapping::identifier},
             {"reference-surface-layers", &images.surface_layers, PreviewMapping::identifier}});
    }
    spiral::fileio::AtomicDirectory set(output, ".pfm .png");
    for (const Output& entry : outputs) {
        const auto pfm = deepgi::encode_pfm(*entry.image);
        set.write_file(std::string(entry.name) + ".pfm", pfm.data(), pfm.size());
        const auto png = deepgi::encode_png(entry.image->width, entry.image->height,
                                            deepgi_app::preview_rgba8(*entry.image, entry.preview));
        set.write_file(std::string(entry.name) + ".png", png.data(), png.size());
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
    if (!images.reflection_radiance.pixels.empty()) {
        long long mirrors = 0, hits = 0;
        for (std::size_t i = 0; i < images.surface_layers.pixels.size() / 3; ++i) {
            if (images.surface_layers.pixels[3 * i + 2] != 1.0f) continue;
            ++mirrors;
            if (images.reflection_hit.pixels[3 * i] >= 0.0f) ++hits;
        }
        fmt::print("reference reflections: {} mirror pixels, {} reflected rays hit a surface\n",
                   mirrors, hits);
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
    app.option_defaults()->always_capture_default();
    spiral_apps::use_help_formatter(app);
    app.add_option("--scene", options.scene,
                   "A built-in scene (listed by deepgi --help) or a .gltf/.glb file");
    app.add_option("--size", options.size,
                   "Viewport size WIDTHxHEIGHT in pixels (guard band added)")
        ->default_str("1280x720 pixels");
    app.add_option("--output", options.output,
                   "Directory for the PFM images and their PNG previews")
        ->default_str("none; reference needs one");
    app.add_option("--rays", options.rays, "Most ambient-visibility rays per pixel")
        ->default_str(fmt::format("{} rays", options.rays));
    app.add_option("--min-rays", options.min_rays, "Fewest ambient-visibility rays per pixel")
        ->default_str(fmt::format("{} rays", options.min_rays));
    app.add_option("--target-error", options.target_error,
                   "Stop adding rays once the standard error of the visibility (a fraction, "
                   "times 1.3) is below this");
    app.add_option("--seed", options.seed, "Random seed (same seed, same images)");
    app.add_option("--threads", options.threads, "Worker threads (0: all hardware threads)")
        ->default_str("0, all hardware threads");
    const deepgi::RenderSettings defaults;
    app.add_option("--ao-radius", options.radius, row_help("ao-radius"))
        ->default_str(spiral_apps::scene_length_default);
    app.add_option("--guard-band", options.guard_band, row_help("guard-band"))
        ->default_str(fmt::format("{} of the height", defaults.guard_band_fraction));
    app.add_option("--min-separation", options.min_separation, row_help("min-separation"))
        ->default_str(spiral_apps::scene_length_default);
    app.add_flag("--no-ao", options.no_ao, "Do not trace ambient visibility");
    app.add_flag("--no-irradiance", options.no_irradiance, "Do not trace one-bounce irradiance");
    app.add_flag("--no-reflections", options.no_reflections,
                 "Do not trace the mirror reflections (scenes with mirrors only)");
    app.add_option("--mirror-roughness", options.mirror_roughness, row_help("mirror-roughness"))
        ->default_str(fmt::format("{}", defaults.mirror_roughness));
    app.add_option("--radiosity-radius", options.radiosity_radius, row_help("radiosity-radius"))
        ->default_str(spiral_apps::scene_length_default);
    app.add_option("--irradiance-rays", options.irradiance_rays,
                   "Most irradiance rays per pixel (cosine directions and emitter shadow rays)")
        ->default_str(fmt::format("{} rays", options.irradiance_rays));
    app.add_option("--irradiance-min-rays", options.irradiance_min_rays,
                   "Fewest irradiance rays per pixel")
        ->default_str(fmt::format("{} rays", options.irradiance_min_rays));
    app.add_option("--irradiance-ceiling-rays", options.irradiance_ceiling_rays,
                   "Most irradiance rays per pixel whose standard error is still at or above "
                   "0.005 after --irradiance-rays")
        ->default_str(fmt::format("{} rays", options.irradiance_ceiling_rays));
    app.add_option("--irradiance-target-error", options.irradiance_target_error,
                   "Stop adding irradiance rays once every channel's standard error (times "
                   "1.3) is below this fraction of E, or 0.002, and below 0.005")
        ->default_str(fmt::format("{} of E", options.irradiance_target_error));
    app.add_option("--bounces", options.bounces,
                   fmt::format("Diffuse bounces K of the irradiance, 1 to {} (E_K: what deep "
                               "radiosity holds after K still frames of --rho-prop 1)",
                               max_bounces))
        ->default_str("1 bounce");
    if (const auto status = parse_command_line(app, argc - 1, argv + 1, "deepgi reference"))
        return *status;
    return run_reporting_errors("deepgi reference", [&] { return run(options); });
}

}  // namespace deepgi_app
