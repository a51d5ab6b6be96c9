// temporal_convergence: how fast a still camera's blurred E and AO approach
// the same estimator's converged image (docs/radiosity.md, "How fast a still
// camera converges"), as a table per scene at the deepgi command line's
// defaults: lengths `auto`, resolved for each scene (--library-lengths: the
// library's fixed 0.5 m AO and 1 m radiosity radii instead). The
// measurement and its figures are tests/runtime/still_convergence.hpp's,
// shared with the ctest that checks the targets.
// --maps DIR writes where the AO error sits (docs/deep-sao-studies.md, "How fast
// the march converges") and the E images that scripts/e_error_where.py reads;
// --check-running-mean checks that no history was lost; --shaders DIR measures
// a folder of edited shader copies, as deepgi --shaders renders one.
#include "bench_harness.hpp"
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/image_io.hpp"
#include "deepgi/renderer.hpp"
#include "still_convergence.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace {

using deepgi::FloatImage;

// --maps: a grey map of |AO - C| / mean occlusion (the table's AO figure per
// pixel), black at 0 and white at 0.5 or more; sky dark blue.
void write_error_map(const std::filesystem::path& path, const FloatImage& ao,
                     const FloatImage& converged, const FloatImage& depth) {
    constexpr double full = 0.5;
    double occlusion = 0.0;
    std::size_t surface = 0;
    for (std::size_t p = 0; p < depth.pixels.size(); ++p)
        if (depth.pixels[p] > 0.0f) occlusion += 1.0 - converged.pixels[p], ++surface;
    occlusion = std::max(occlusion / double(std::max<std::size_t>(surface, 1)), 1e-30);
    std::vector<std::uint8_t> rgba(depth.pixels.size() * 4, 255);
    for (std::size_t p = 0; p < depth.pixels.size(); ++p) {
        const double e = std::abs(ao.pixels[p] - converged.pixels[p]) / occlusion / full;
        const auto g = std::uint8_t(std::lround(255.0 * std::clamp(e, 0.0, 1.0)));
        rgba[4 * p] = rgba[4 * p + 1] = rgba[4 * p + 2] = depth.pixels[p] > 0.0f ? g : 0;
        if (depth.pixels[p] <= 0.0f) rgba[4 * p + 2] = 96;  // sky: dark blue
    }
    deepgi::write_png(path, depth.width, depth.height, rgba);
}

// --maps: the blurred E and layer 0's filtered E before the blur, as PFM
// (`{scene}-e-{tag}.pfm`, `{scene}-e-unblurred-{tag}.pfm`), for finding
// where E's error sits (docs/radiosity-studies.md, "Where cornell's error
// after 16 frames sits").
void write_e_images(const std::filesystem::path& folder, const std::string& scene,
                    const std::string& tag, const deepgi::Renderer& renderer, int width,
                    int height) {
    using deepgi::convergence::viewport_of;
    deepgi::write_pfm(folder / fmt::format("{}-e-{}.pfm", scene, tag),
                      viewport_of(renderer.read_pass_output("radiosity-blurred"), width, height));
    deepgi::write_pfm(
        folder / fmt::format("{}-e-unblurred-{}.pfm", scene, tag),
        viewport_of(renderer.read_pass_output("radiosity-irradiance-layer0"), width, height));
}

// --check-running-mean: for a still camera the filtered AO (`ao-temporal`,
// before the blur) must be the plain mean of every raw frame so far, below
// the history cap. A texel that differs had its history dropped or capped.
void add_raw_ao(const deepgi::Renderer& renderer, std::vector<double>& sum) {
    const FloatImage raw = renderer.read_pass_output("ao-raw");
    sum.resize(raw.pixels.size(), 0.0);
    for (std::size_t p = 0; p < raw.pixels.size(); ++p) sum[p] += raw.pixels[p];
}

void print_running_mean_check(const deepgi::Renderer& renderer, const std::vector<double>& sum,
                              const std::string& scene, int frames) {
    const FloatImage filtered = renderer.read_pass_output("ao-temporal");
    const FloatImage depth = renderer.read_pass_output("depth_pyramid-level0");
    int differ = 0, surface = 0;
    double worst = 0.0;
    for (std::size_t p = 0; p < filtered.pixels.size(); ++p) {
        if (depth.pixels[p * depth.channels] <= 0.0f) continue;
        ++surface;
        const double d = std::abs(filtered.pixels[p] - sum[p] / frames);
        worst = std::max(worst, d);
        if (d > 1e-4) ++differ;
    }
    fmt::print(
        "<!-- {}, {} frames: filtered AO differs from the mean of the raw frames by "
        "over 1e-4 at {} of {} surface texels (largest {:.2g}) -->\n",
        scene, frames, differ, surface, worst);
}

}  // namespace

int main(int argc, char** argv) {
    deepgi::bench::Options options;
    options.size = "320x180";
    options.scenes = {"cornell", "atrium", "warehouse"};
    std::vector<int> counts{16, 64};
    int converged_frames = deepgi::convergence::default_converged_frames;
    int converged_taps = deepgi::convergence::default_converged_taps;
    // Another realisation of the same renderer, for the run-to-run spread
    // (docs/radiosity-studies.md, "How fast a still camera converges").
    int rotation_seed = 0;
    int temporal_offset = 0;
    CLI::App app{"temporal_convergence: still-camera E and AO against the converged image"};
    deepgi::bench::add_options(app, options);
    app.add_option("--frames-list", counts, "still frame counts at which to measure")
        ->delimiter(',');
    app.add_option("--converged-frames", converged_frames, "frames of the converged image");
    app.add_option("--converged-taps", converged_taps, "radiosity taps of the converged image");
    app.add_option("--rotation-seed", rotation_seed,
                   "per-pixel rotation field (the renderer's rotation-seed setting)");
    app.add_option("--temporal-offset", temporal_offset,
                   "first point of the frame sequence (the renderer's temporal-offset setting)");
    std::string maps;
    std::string shaders;
    bool check_running_mean = false;
    bool library_lengths = false;
    app.add_option("--maps", maps,
                   "folder for AO error maps (|AO - C| / mean occlusion, white at 0.5), the "
                   "blurred, raw, unblurred (filtered) and converged AO, the blurred, unblurred "
                   "and converged E, depth and normals as PFM");
    app.add_option("--shaders", shaders,
                   "folder searched for shader files before the build's (edited copies), for both "
                   "the measured renderer and the converged image");
    app.add_flag("--check-running-mean", check_running_mean,
                 "check that the filtered AO is the mean of the raw frames (a readback a frame)");
    app.add_flag("--library-lengths", library_lengths,
                 "lengths at the library's defaults (AO radius 0.5 m, radiosity 1 m) instead of "
                 "the command line's auto, a fraction of each scene's size; --set still wins");
    CLI11_PARSE(app, argc, argv);
    return deepgi::bench::run("temporal_convergence", [&] {
        deepgi::bench::finish(options);
        for (int n : counts)
            if (n < 1) throw deepgi::InputError("--frames-list: counts must be >= 1");
        if (converged_frames < 1) throw deepgi::InputError("--converged-frames must be >= 1");
        if (converged_taps < 1) throw deepgi::InputError("--converged-taps must be >= 1");
        if (std::error_code error;
            !shaders.empty() && !std::filesystem::is_directory(shaders, error))
            throw deepgi::InputError(fmt::format("--shaders {}: not a folder", shaders));
        // --set values go on top of the lengths, so an explicit length wins.
        deepgi::RenderSettings settings = deepgi::bench::settings_for(
            options, library_lengths ? deepgi::RenderSettings{} : deepgi::with_auto_lengths({}));
        settings.rotation_seed = rotation_seed;
        settings.temporal_offset = temporal_offset;
        deepgi::validate(settings);
        deepgi::HeadlessContext context;
        // The measurement renders the counts in order, from one renderer.
        std::sort(counts.begin(), counts.end());
        counts.erase(std::unique(counts.begin(), counts.end()), counts.end());
        fmt::print(
            "| scene | frames | E rel. RMS | E rel. MAE | E fine grain / converged's | "
            "AO RMS / mean occlusion | AO fine grain / converged's |\n"
            "|---|--:|--:|--:|--:|--:|--:|\n");
        for (const auto& name : options.scenes) {
            const deepgi::Scene scene = deepgi::load_scene(name);
            const std::filesystem::path folder(maps);
            if (!maps.empty()) std::filesystem::create_directories(folder);
            FloatImage converged_ao, depth;
            std::vector<double> raw_sum;  // --check-running-mean: the raw AO summed over frames
            deepgi::convergence::StillObserver observer;
            if (!maps.empty())
                observer.converged = [&](const FloatImage& ao, const FloatImage& d) {
                    converged_ao = ao;
                    depth = d;
                    deepgi::write_pfm(folder / fmt::format("{}-ao-converged.pfm", name), ao);
                    deepgi::write_pfm(folder / fmt::format("{}-depth.pfm", name), d);
                };
            if (!maps.empty())
                observer.converged_renderer = [&](const deepgi::Renderer& dense) {
                    write_e_images(folder, name, "converged", dense, options.width, options.height);
                    deepgi::write_pfm(folder / fmt::format("{}-normal.pfm", name),
                                      deepgi::convergence::viewport_of(
                                          dense.read_pass_output("gbuffer-normal-layer0"),
                                          options.width, options.height));
                    deepgi::write_pfm(
                        folder / fmt::format("{}-ao-temporal-converged.pfm", name),
                        deepgi::convergence::viewport_of(dense.read_pass_output("ao-temporal"),
                                                         options.width, options.height));
                };
            if (check_running_mean)
                observer.frame = [&](const deepgi::Renderer& renderer) {
                    add_raw_ao(renderer, raw_sum);
                };
            if (!maps.empty() || check_running_mean)
                observer.count = [&](const deepgi::Renderer& renderer, int n,
                                     const FloatImage& ao) {
                    if (check_running_mean) print_running_mean_check(renderer, raw_sum, name, n);
                    if (maps.empty()) return;
                    write_error_map(folder / fmt::format("{}-ao-error-{}.png", name, n), ao,
                                    converged_ao, depth);
                    deepgi::write_pfm(folder / fmt::format("{}-ao-{}.pfm", name, n), ao);
                    write_e_images(folder, name, std::to_string(n), renderer, options.width,
                                   options.height);
                    deepgi::write_pfm(
                        folder / fmt::format("{}-ao-raw-{}.pfm", name, n),
                        deepgi::convergence::viewport_of(renderer.read_pass_output("ao-raw"),
                                                         options.width, options.height));
                    deepgi::write_pfm(
                        folder / fmt::format("{}-ao-temporal-{}.pfm", name, n),
                        deepgi::convergence::viewport_of(renderer.read_pass_output("ao-temporal"),
                                                         options.width, options.height));
                };
            const deepgi::convergence::StillConvergence run =
                deepgi::convergence::measure_still_convergence(
                    scene, settings, counts, converged_taps, converged_frames, observer, shaders);
            // A converged image with no grain at all (a flat test shader) has
            // no ratio: "-" rather than nan.
            const auto ratio = [](double grain, double converged) {
                return converged > 0.0 ? fmt::format("{:.2f}", grain / converged)
                                       : std::string("-");
            };
            for (const deepgi::convergence::StillFigures& row : run.rows) {
                fmt::print(
                    "| {} | {} | {:.2f}% | {:.2f}% | {} ({:.2f}% / {:.2f}%) | {:.2f}% | "
                    "{} ({:.2f}% / {:.2f}%) |\n",
                    name, row.frames, 100.0 * row.e_rms, 100.0 * row.e_mae,
                    ratio(row.e_grain, run.converged_e_grain), 100.0 * row.e_grain,
                    100.0 * run.converged_e_grain, 100.0 * row.ao_rms,
                    ratio(row.ao_grain, run.converged_ao_grain), 100.0 * row.ao_grain,
                    100.0 * run.converged_ao_grain);
            }
            fmt::print("<!-- {}: {} flat pixels of {} -->\n", name, run.flat_pixels, run.pixels);
            const deepgi::SceneScale scale = deepgi::scene_scale(scene);
            for (const std::string& line : deepgi::describe_auto_lengths(
                     settings, deepgi::resolve_auto_lengths(settings, scale), scale))
                fmt::print("<!-- {}: {} -->\n", name, line);
        }
        fmt::print(
            "\nconverged: {} radiosity taps, {} still frames; device: {} | {}x{} | lengths "
            "{}{}{}\n",
            converged_taps, converged_frames, deepgi::query_context_info().renderer, options.width,
            options.height, library_lengths ? "the library's" : "auto",
            deepgi::bench::set_settings_note(options),
            shaders.empty() ? "" : fmt::format(" | shaders first from {}", shaders));
        return 0;
    });
}
