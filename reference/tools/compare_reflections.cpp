// deepgi_compare_reflections DUMP_DIR REFERENCE_DIR GUARD_PIXELS
// Compares the reflection pass of `deepgi --headless --dump` against the
// traced mirror reflections of `deepgi reference` on the same scene, size and
// guard band (docs/reflections.md, "Against the ray tracer"), over the mirror
// pixels of the viewport (guard band excluded) where both call the pixel a
// mirror and the traced and rasterised layer-0 depths agree:
//   - same surface: the renderer's hit (texel and layer of `reflection-hit`)
//     is mapped to a surface by the reference's own camera rays through that
//     texel (`reference-surface-layers`, the surface the layer stores there),
//     and compared with the surface the traced ray hits; a miss (the
//     environment) on both sides counts as the same;
//   - radiance: this frame's `reflection-radiance` and, when dumped, the
//     filtered `reflection-temporal`, against the traced L(y): relative mean
//     absolute error sum|L - L_ref| / sum L_ref and bias sum(L - L_ref) /
//     sum L_ref, over the three channels; and the filtered radiance's over
//     the pixels whose surface agrees, which leaves out the march's misses
//     and keeps the shading's own error (the hit texel's lit radiance).
// Prints one line of key=value pairs.
#include "deepgi/image_io.hpp"
#include "dump_frame.hpp"
#include "tool_arguments.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

namespace {

int run(int argc, char** argv) {
    CLI::App app{
        "The reflection pass of a dump against the traced mirror reflections (docs/reflections.md)",
        "deepgi_compare_reflections"};
    deepgi_tools::use_tool_layout(app);
    std::filesystem::path dump, reference;
    int guard = 0;
    deepgi_tools::add_dump_dir(app, dump);
    deepgi_tools::add_reference_dir(app, reference);
    deepgi_tools::add_guard_pixels(app, guard);
    if (const auto status = deepgi_tools::parse(app, argc, argv)) return *status;
    const auto raster = deepgi::read_pfm(dump / "gbuffer-depth-layer0.pfm");
    const auto hit = deepgi::read_pfm(dump / "reflection-hit.pfm");
    const auto radiance = deepgi::read_pfm(dump / "reflection-radiance.pfm");
    const bool has_filtered = std::filesystem::exists(dump / "reflection-temporal.pfm");
    const deepgi::FloatImage filtered =
        has_filtered ? deepgi::read_pfm(dump / "reflection-temporal.pfm") : radiance;
    const auto traced = deepgi::read_pfm(reference / "reference-depth-layer0.pfm");
    const auto truth = deepgi::read_pfm(reference / "reference-reflection-radiance.pfm");
    const auto truth_hit = deepgi::read_pfm(reference / "reference-reflection-hit.pfm");
    const auto layers = deepgi::read_pfm(reference / "reference-surface-layers.pfm");
    if (raster.width != truth.width || raster.height != truth.height || hit.width != truth.width ||
        hit.height != truth.height || truth.channels != 3 || hit.channels < 3 ||
        layers.channels != 3 || radiance.channels < 3) {
        fmt::print(stderr, "size mismatch: dump {}x{}, reference {}x{}\n", raster.width,
                   raster.height, truth.width, truth.height);
        return 2;
    }
    long long mirrors = 0, same = 0, both_miss = 0, missed = 0, wrong = 0, extra = 0;
    double truth_sum = 0.0, error_sum = 0.0, bias_sum = 0.0, filtered_error = 0.0,
           filtered_bias = 0.0, same_truth = 0.0, same_error = 0.0, same_bias = 0.0;
    for (int y = guard; y < truth.height - guard; ++y)
        for (int x = guard; x < truth.width - guard; ++x) {
            if (!deepgi_tools::same_surface(raster.at(x, y), traced.at(x, y))) continue;
            if (layers.at(x, y, 2) != 1.0f || hit.at(x, y, 2) <= -2.0f) continue;
            ++mirrors;
            const int layer = int(hit.at(x, y, 2));
            int surface = -1;
            if (layer >= 0) {
                const int hx = std::clamp(int(std::floor(hit.at(x, y, 0))), 0, hit.width - 1);
                const int hy = std::clamp(int(std::floor(hit.at(x, y, 1))), 0, hit.height - 1);
                surface = int(layers.at(hx, hy, std::min(layer, 1)));
            }
            const int expected = int(truth_hit.at(x, y, 0));
            if (surface == expected) {
                ++same;
                if (expected < 0) ++both_miss;
            } else if (surface < 0) {
                ++missed;
            } else if (expected < 0) {
                ++extra;
            } else {
                ++wrong;
            }
            for (int c = 0; c < 3; ++c) {
                const double t = truth.at(x, y, c);
                truth_sum += t;
                error_sum += std::abs(radiance.at(x, y, c) - t);
                bias_sum += radiance.at(x, y, c) - t;
                filtered_error += std::abs(filtered.at(x, y, c) - t);
                filtered_bias += filtered.at(x, y, c) - t;
                if (surface == expected) {
                    same_truth += t;
                    same_error += std::abs(filtered.at(x, y, c) - t);
                    same_bias += filtered.at(x, y, c) - t;
                }
            }
        }
    const double n = std::max(mirrors, 1LL), sum = std::max(truth_sum, 1e-30);
    fmt::print(
        "mirror_pixels={} same_surface={:.4f} both_miss={:.4f} renderer_missed={:.4f} "
        "wrong_surface={:.4f} renderer_only={:.4f} mean_truth={:.4g} rel_mae={:.4f} "
        "rel_bias={:+.4f} filtered_rel_mae={:.4f} filtered_rel_bias={:+.4f} "
        "same_surface_filtered_rel_mae={:.4f} same_surface_filtered_rel_bias={:+.4f}\n",
        mirrors, same / n, both_miss / n, missed / n, wrong / n, extra / n, truth_sum / (3.0 * n),
        error_sum / sum, bias_sum / sum, filtered_error / sum, filtered_bias / sum,
        same_error / std::max(same_truth, 1e-30), same_bias / std::max(same_truth, 1e-30));
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return deepgi_tools::run_tool("deepgi_compare_reflections", argc, argv, run);
}
