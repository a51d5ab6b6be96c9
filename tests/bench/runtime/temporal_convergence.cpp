// temporal_convergence: how fast a still camera's blurred E and AO approach
// the same estimator's converged image (docs/radiosity.md, "Temporal
// accumulation"). Per scene, default settings:
//   - the build's renderer renders --frames-list still frames; at each count
//     the blurred E (`radiosity-blurred`) and AO (`ao-blurred`) are read;
//   - the converged image: a renderer whose radiosity gather uses
//     --converged-taps taps (a header written at run time), after
//     --converged-frames still frames, so its E is the running mean of that
//     many frames of a gather that many times denser, and its AO the running
//     mean of that many frames.
// Figures: E relative RMS sqrt(sum (E - C)^2 / sum C^2) and relative MAE
// sum |E - C| / sum C over the viewport's surface pixels; AO RMS of AV - C
// over the mean occlusion 1 - C; fine grain: the relative RMS of a value
// minus its 9x9 box mean over pixels whose window lies on one plane of one
// albedo, for the image and for the converged one.
// --maps DIR writes where the AO error sits (docs/deep-sao.md, "How fast the
// march converges"); --check-running-mean checks that no history was lost.
#include "bench_harness.hpp"
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/image_io.hpp"
#include "deepgi/renderer.hpp"
#include "study_headers.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>

namespace {

using deepgi::FloatImage;

// The viewport part of an internal-size image (the guard band cut off), or
// the image itself when it already has the viewport's size.
FloatImage viewport_of(const FloatImage& image, int width, int height) {
    if (image.width == width && image.height == height) return image;
    const int gx = (image.width - width) / 2;
    const int gy = (image.height - height) / 2;
    FloatImage out{width, height, image.channels,
                   std::vector<float>(std::size_t(width) * height * image.channels)};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < image.channels; ++c)
                out.pixels[(std::size_t(y) * width + x) * image.channels + c] =
                    image.at(x + gx, y + gy, c);
    return out;
}

struct Guides {
    FloatImage depth, normal, albedo;  // viewport size
};

struct Images {
    FloatImage e, ao;  // blurred, viewport size
};

Images read_images(const deepgi::Renderer& renderer, int width, int height) {
    return {viewport_of(renderer.read_pass_output("radiosity-blurred"), width, height),
            viewport_of(renderer.read_pass_output("ao-blurred"), width, height)};
}

// Pixels whose 9x9 window lies on one plane of one albedo: same normal
// (cos >= 0.999), same albedo (1e-3), depth within 5% of the centre's.
std::vector<std::size_t> flat_pixels(const Guides& guides) {
    const int w = guides.depth.width, h = guides.depth.height, r = 4;
    std::vector<std::size_t> out;
    for (int y = r; y < h - r; ++y) {
        for (int x = r; x < w - r; ++x) {
            const float d = guides.depth.at(x, y, 0);
            if (d <= 0.0f) continue;
            bool flat = true;
            for (int v = -r; v <= r && flat; ++v) {
                for (int u = -r; u <= r && flat; ++u) {
                    const float dd = guides.depth.at(x + u, y + v, 0);
                    float cos = 0.0f, albedo = 0.0f;
                    for (int c = 0; c < 3; ++c) {
                        cos += guides.normal.at(x, y, c) * guides.normal.at(x + u, y + v, c);
                        albedo = std::max(albedo, std::abs(guides.albedo.at(x, y, c) -
                                                           guides.albedo.at(x + u, y + v, c)));
                    }
                    flat = dd > 0.0f && std::abs(dd - d) <= 0.05f * d && cos >= 0.999f &&
                           albedo <= 1e-3f;
                }
            }
            if (flat) out.push_back(std::size_t(y) * w + x);
        }
    }
    return out;
}

// Relative RMS of the image minus its 9x9 box mean over `pixels`, against
// the image's RMS there (AO: against the mean occlusion).
double fine_grain(const FloatImage& image, const std::vector<std::size_t>& pixels, bool ao) {
    const int w = image.width, ch = ao ? 1 : 3;
    double squared = 0.0, norm = 0.0;
    for (std::size_t p : pixels) {
        const int x = int(p % w), y = int(p / w);
        for (int c = 0; c < ch; ++c) {
            double box = 0.0;
            for (int v = -4; v <= 4; ++v)
                for (int u = -4; u <= 4; ++u) box += image.at(x + u, y + v, c);
            box /= 81.0;
            const double value = image.at(x, y, c);
            squared += (value - box) * (value - box);
            norm += ao ? (1.0 - box) : value * value;
        }
    }
    if (pixels.empty()) return 0.0;
    return ao ? std::sqrt(squared / double(pixels.size())) / (norm / double(pixels.size()))
              : std::sqrt(squared / std::max(norm, 1e-30));
}

struct Errors {
    double e_rms = 0.0, e_mae = 0.0, ao_rms = 0.0;
};

Errors errors(const Images& image, const Images& converged, const FloatImage& depth) {
    double e2 = 0.0, c2 = 0.0, e1 = 0.0, c1 = 0.0, a2 = 0.0, occlusion = 0.0;
    std::size_t surface = 0;
    for (std::size_t p = 0; p < depth.pixels.size(); ++p) {
        if (depth.pixels[p] <= 0.0f) continue;
        ++surface;
        for (int c = 0; c < 3; ++c) {
            const double e = image.e.pixels[3 * p + c], t = converged.e.pixels[3 * p + c];
            e2 += (e - t) * (e - t);
            c2 += t * t;
            e1 += std::abs(e - t);
            c1 += std::abs(t);
        }
        const double a = image.ao.pixels[p], t = converged.ao.pixels[p];
        a2 += (a - t) * (a - t);
        occlusion += 1.0 - t;
    }
    return {std::sqrt(e2 / std::max(c2, 1e-30)), e1 / std::max(c1, 1e-30),
            std::sqrt(a2 / double(std::max<std::size_t>(surface, 1))) /
                std::max(occlusion / double(std::max<std::size_t>(surface, 1)), 1e-30)};
}

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
    int converged_frames = 256;
    int converged_taps = 76;
    std::string maps;
    bool check_running_mean = false;
    CLI::App app{"temporal_convergence: still-camera E and AO against the converged image"};
    deepgi::bench::add_options(app, options);
    app.add_option("--frames-list", counts, "still frame counts at which to measure")
        ->delimiter(',');
    app.add_option("--converged-frames", converged_frames, "frames of the converged image");
    app.add_option("--converged-taps", converged_taps, "radiosity taps of the converged image");
    app.add_option("--maps", maps,
                   "folder for AO error maps (|AO - C| / mean occlusion, white at 0.5) and the "
                   "blurred, raw and converged AO as PFM");
    app.add_flag("--check-running-mean", check_running_mean,
                 "check that the filtered AO is the mean of the raw frames (a readback a frame)");
    CLI11_PARSE(app, argc, argv);
    return deepgi::bench::run("temporal_convergence", [&] {
        deepgi::bench::finish(options);
        for (int n : counts)
            if (n < 1) throw deepgi::InputError("--frames-list: counts must be >= 1");
        if (converged_frames < 1) throw deepgi::InputError("--converged-frames must be >= 1");
        if (converged_taps < 1) throw deepgi::InputError("--converged-taps must be >= 1");
        const deepgi::RenderSettings settings = deepgi::bench::settings_for(options);
        deepgi::validate(settings);
        deepgi::HeadlessContext context;
        deepgi::study::ScratchFolder folder;
        {
            std::ofstream header(folder.path() / "radiosity_taps.glsl");
            header << spiral::codegen::make_gather_header(
                "radiosity", converged_taps, std::nullopt,
                {fmt::format("temporal_convergence --converged-taps {}", converged_taps)});
        }
        const deepgi::ShaderLoader dense_loader =
            deepgi::study::loader_with_override(folder.path());
        const int w = options.width, h = options.height;
        fmt::print(
            "| scene | frames | E rel. RMS | E rel. MAE | E fine grain / converged's | "
            "AO RMS / mean occlusion | AO fine grain / converged's |\n"
            "|---|--:|--:|--:|--:|--:|--:|\n");
        std::string measured;
        for (const auto& name : options.scenes) {
            const deepgi::Scene scene = deepgi::load_scene(name);
            deepgi::Renderer dense(scene, settings, dense_loader);
            for (int i = 0; i < converged_frames; ++i) dense.render(scene.default_camera);
            const Images converged = read_images(dense, w, h);
            const Guides guides{viewport_of(dense.read_pass_output("gbuffer-depth-layer0"), w, h),
                                viewport_of(dense.read_pass_output("gbuffer-normal-layer0"), w, h),
                                viewport_of(dense.read_pass_output("gbuffer-albedo-layer0"), w, h)};
            const std::vector<std::size_t> flat = flat_pixels(guides);
            if (!maps.empty()) {
                std::filesystem::create_directories(maps);
                deepgi::write_pfm(
                    std::filesystem::path(maps) / fmt::format("{}-ao-converged.pfm", name),
                    converged.ao);
                deepgi::write_pfm(std::filesystem::path(maps) / fmt::format("{}-depth.pfm", name),
                                  guides.depth);
            }
            const double converged_e_grain = fine_grain(converged.e, flat, false);
            const double converged_ao_grain = fine_grain(converged.ao, flat, true);
            deepgi::Renderer renderer(scene, settings,
                                      deepgi::ShaderLoader::from_build_configuration());
            int rendered = 0;
            std::vector<double> raw_sum;  // --check-running-mean: the raw AO summed over frames
            for (int n : counts) {
                while (rendered < n) {
                    renderer.render(scene.default_camera);
                    ++rendered;
                    if (check_running_mean) add_raw_ao(renderer, raw_sum);
                }
                if (check_running_mean) print_running_mean_check(renderer, raw_sum, name, n);
                const Images image = read_images(renderer, w, h);
                if (!maps.empty()) {
                    const std::filesystem::path folder(maps);
                    write_error_map(folder / fmt::format("{}-ao-error-{}.png", name, n), image.ao,
                                    converged.ao, guides.depth);
                    deepgi::write_pfm(folder / fmt::format("{}-ao-{}.pfm", name, n), image.ao);
                    deepgi::write_pfm(folder / fmt::format("{}-ao-raw-{}.pfm", name, n),
                                      viewport_of(renderer.read_pass_output("ao-raw"), w, h));
                }
                const Errors error = errors(image, converged, guides.depth);
                fmt::print(
                    "| {} | {} | {:.2f}% | {:.2f}% | {:.2f} ({:.2f}% / {:.2f}%) | {:.2f}% | "
                    "{:.2f} ({:.2f}% / {:.2f}%) |\n",
                    name, n, 100.0 * error.e_rms, 100.0 * error.e_mae,
                    fine_grain(image.e, flat, false) / converged_e_grain,
                    100.0 * fine_grain(image.e, flat, false), 100.0 * converged_e_grain,
                    100.0 * error.ao_rms, fine_grain(image.ao, flat, true) / converged_ao_grain,
                    100.0 * fine_grain(image.ao, flat, true), 100.0 * converged_ao_grain);
            }
            fmt::print("<!-- {}: {} flat pixels of {} -->\n", name, flat.size(), w * h);
            measured = deepgi::bench::measured_on(renderer, options);
        }
        fmt::print("\nconverged: {} radiosity taps, {} still frames; {}\n", converged_taps,
                   converged_frames, measured);
        return 0;
    });
}
