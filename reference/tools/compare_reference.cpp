// deepgi_compare_reference DUMP_DIR REFERENCE_DIR GUARD_PIXELS
// Compares `deepgi --headless --dump` against `deepgi reference` on the same
// scene, size and guard band: first the reconstruction (layer-0 depth of the
// camera rays against the rasterised depth), then the deep SAO visibility
// before and after the blur against the ray-traced AV, over the viewport
// (guard band excluded) where both see a surface.
//
// The raw visibility is compared as the pass writes it (signed for the
// solid-angle method: the estimator's own error); the blurred one as compose
// uses it, clamped to [0, 1]. The blurred one is compared a second time
// against the "visible truth": the reference AV plus the occlusion of
// occluders that neither G-buffer layer sees (reference-ao-occlusion-split.pfm),
// which is what a perfect estimator over both layers would reach, and once
// more against what one over layer 0 alone would reach (plus the occlusion
// only layer 1 sees). The difference between the lines is what the G-buffer
// lacks; what remains against the visible truth is the estimator's error.
// Last, where the blurred bias sits: the share of it held by the 5% of rows
// that carry the most, and which rows those are (counted from the top of the
// viewport). A share far above 5% names a band of the view, such as the
// surfaces level with the eye, which the G-buffer samples edge-on.
#include "deepgi/image_io.hpp"
#include "dump_frame.hpp"
#include "tool_arguments.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace {

int run(int argc, char** argv) {
    CLI::App app{"Deep SAO of a dump against the ray-traced ambient visibility (docs/reference.md)",
                 "deepgi_compare_reference"};
    deepgi_tools::use_tool_layout(app);
    deepgi_tools::DumpAndReference folders;
    deepgi_tools::add_dump_and_reference(app, folders);
    const auto& [dump, reference, guard] = folders;
    if (const auto status = deepgi_tools::parse(app, argc, argv)) return *status;
    const auto raster = deepgi::read_pfm(dump / "gbuffer-depth-layer0.pfm");
    const auto traced = deepgi::read_pfm(reference / "reference-depth-layer0.pfm");
    if (raster.width != traced.width || raster.height != traced.height) {
        fmt::print(stderr, "size mismatch: dump {}x{}, reference {}x{}\n", raster.width,
                   raster.height, traced.width, traced.height);
        return 2;
    }
    std::vector<double> relative;
    long long coverage_mismatch = 0;
    for (std::size_t i = 0; i < raster.pixels.size(); ++i) {
        const float a = raster.pixels[i], b = traced.pixels[i];
        if ((a > 0.0f) != (b > 0.0f)) ++coverage_mismatch;
        if (a > 0.0f && b > 0.0f) relative.push_back(std::abs(double(a) - b) / b);
    }
    std::sort(relative.begin(), relative.end());
    auto quantile = [&](double q) {
        return relative.empty() ? 0.0 : relative[std::size_t(q * double(relative.size() - 1))];
    };
    fmt::print(
        "depth: {} pixels, relative error median {:.3g}, 99% {:.3g}, max {:.3g}; "
        "{} pixels hit in one but not the other\n",
        relative.size(), quantile(0.5), quantile(0.99), quantile(1.0), coverage_mismatch);

    const auto truth = deepgi::read_pfm(reference / "reference-ao-visibility.pfm");
    const auto split = deepgi::read_pfm(reference / "reference-ao-occlusion-split.pfm");
    if (split.channels != 3 || split.width != truth.width || split.height != truth.height) {
        fmt::print(stderr, "reference-ao-occlusion-split.pfm is not 3 channels of {}x{}\n",
                   truth.width, truth.height);
        return 2;
    }
    // Occlusion that an estimator reading `layers` G-buffer layers has no
    // surface for: split channel 2 (neither layer), plus channel 1 (only
    // layer 1) for one layer.
    auto unseen = [&](int x, int y, int layers) {
        return double(split.at(x, y, 2)) + (layers == 1 ? split.at(x, y, 1) : 0.0f);
    };
    struct Comparison {
        std::string label;
        std::string output;
        bool clamp;          // as compose uses it
        int visible_layers;  // 0: against the full truth
    };
    const Comparison comparisons[] = {
        {"ao-raw", "ao-raw", false, 0},
        {"ao-blurred", "ao-blurred", true, 0},
        {"ao-blurred vs visible truth (both layers)", "ao-blurred", true, 2},
        {"ao-blurred vs visible truth (layer 0)", "ao-blurred", true, 1},
    };
    std::vector<double> row_bias(std::size_t(truth.height), 0.0);  // blurred vs truth
    long long row_bias_pixels = 0;
    for (const Comparison& comparison : comparisons) {
        const auto estimate = deepgi::read_pfm(dump / (comparison.output + ".pfm"));
        const bool by_row = comparison.label == "ao-blurred";
        double sum_abs = 0.0, sum = 0.0;
        long long count = 0, open = 0, open_dark = 0;
        for (int y = guard; y < truth.height - guard; ++y) {
            for (int x = guard; x < truth.width - guard; ++x) {
                // Only where both agree on the surface: silhouette pixels
                // would compare different points.
                if (!deepgi::same_surface_depth(raster.at(x, y), traced.at(x, y))) continue;
                const double value = comparison.clamp
                                         ? std::clamp(double(estimate.at(x, y)), 0.0, 1.0)
                                         : double(estimate.at(x, y));
                const double target =
                    truth.at(x, y) +
                    (comparison.visible_layers > 0 ? unseen(x, y, comparison.visible_layers) : 0.0);
                const double error = value - target;
                sum_abs += std::abs(error);
                sum += error;
                ++count;
                if (by_row) row_bias[std::size_t(y)] += error;
                // Open surface: nothing within r in the truth.
                if (truth.at(x, y) >= 0.9999f) {
                    ++open;
                    if (value < 0.99) ++open_dark;
                }
            }
        }
        fmt::print("{}: {} pixels, MAE {:.4f}, bias {:+.4f}, open pixels below 0.99: {} of {}\n",
                   comparison.label, count, count ? sum_abs / count : 0.0,
                   count ? sum / count : 0.0, open_dark, open);
        if (by_row) row_bias_pixels = count;
    }
    std::vector<int> rows;
    for (int y = guard; y < truth.height - guard; ++y) rows.push_back(y);
    std::sort(rows.begin(), rows.end(),
              [&](int a, int b) { return row_bias[std::size_t(a)] > row_bias[std::size_t(b)]; });
    const std::size_t top = std::max<std::size_t>(1, rows.size() / 20);
    double total = 0.0, carried = 0.0;
    for (int y : rows) total += row_bias[std::size_t(y)];
    std::vector<int> from_top;
    for (std::size_t k = 0; k < top && k < rows.size(); ++k) {
        carried += row_bias[std::size_t(rows[k])];
        from_top.push_back(truth.height - 1 - guard - rows[k]);  // PFM rows run bottom to top
    }
    std::sort(from_top.begin(), from_top.end());
    if (row_bias_pixels > 0 && !from_top.empty())
        fmt::print(
            "ao-blurred bias by row: the {} rows ({:.0f}%) carrying the most hold {:+.4f} of "
            "{:+.4f}; viewport rows from the top {}\n",
            from_top.size(), 100.0 * double(from_top.size()) / double(rows.size()),
            carried / double(row_bias_pixels), total / double(row_bias_pixels),
            fmt::join(from_top, ","));
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return deepgi_tools::run_tool("deepgi_compare_reference", argc, argv, run);
}
