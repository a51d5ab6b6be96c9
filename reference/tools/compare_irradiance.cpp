// deepgi_compare_irradiance DUMP_DIR REFERENCE_DIR GUARD_PIXELS
// Compares deep radiosity's layer-0 irradiance from `deepgi --headless --dump`
// against the ray-traced one-bounce irradiance of `deepgi reference` on the
// same scene, size and guard band, over the viewport (guard band excluded)
// where the traced and the rasterised layer-0 depth agree. For each dumped
// image (one frame's raw gather, the temporally filtered E, the blurred E):
// mean absolute error, bias and the relative error sum|E - E_ref| / sum E_ref,
// averaged over the three channels; also the share of pixels the gather left
// without a sample (confidence 0). First it checks the light model: the dumped
// direct light against the traced direct light at the same points.
#include "deepgi/image_io.hpp"
#include "dump_frame.hpp"
#include "tool_arguments.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace {

int run(int argc, char** argv) {
    CLI::App app{
        "Deep radiosity's layer-0 irradiance of a dump against the ray-traced one-bounce "
        "irradiance (docs/reference.md)",
        "deepgi_compare_irradiance"};
    deepgi_tools::use_tool_layout(app);
    deepgi_tools::DumpAndReference folders;
    deepgi_tools::add_dump_and_reference(app, folders);
    const auto& [dump, reference, guard] = folders;
    if (const auto status = deepgi_tools::parse(app, argc, argv)) return *status;
    const auto raster = deepgi::read_pfm(dump / "gbuffer-depth-layer0.pfm");
    const auto traced = deepgi::read_pfm(reference / "reference-depth-layer0.pfm");
    const auto truth = deepgi::read_pfm(reference / "reference-irradiance.pfm");
    const auto truth_error =
        deepgi::read_pfm(reference / "reference-irradiance-standard-error.pfm");
    const auto confidence = deepgi::read_pfm(dump / "radiosity-confidence-layer0.pfm");
    if (raster.width != truth.width || raster.height != truth.height || truth.channels != 3) {
        fmt::print(stderr, "size mismatch: dump {}x{}, reference {}x{}\n", raster.width,
                   raster.height, truth.width, truth.height);
        return 2;
    }
    auto compared = [&](int x, int y) {
        // Only where both agree on the surface: silhouette pixels would
        // compare different points.
        return deepgi::same_surface_depth(raster.at(x, y), traced.at(x, y));
    };
    double truth_sum = 0.0, truth_error_sum = 0.0;
    long long count = 0, empty = 0;
    for (int y = guard; y < truth.height - guard; ++y)
        for (int x = guard; x < truth.width - guard; ++x) {
            if (!compared(x, y)) continue;
            ++count;
            if (confidence.at(x, y) <= 0.0f) ++empty;
            for (int c = 0; c < 3; ++c) {
                truth_sum += truth.at(x, y, c);
                truth_error_sum += truth_error.at(x, y, c);
            }
        }
    const double n = double(std::max(count, 1LL)) * 3.0;

    // The light model first: the direct light pass against the traced
    // direct light at the same points (they differ where the shadow map
    // and its filtering differ from an exact shadow ray).
    {
        const auto raster_direct = deepgi::read_pfm(dump / "direct_light-radiance-layer0.pfm");
        const auto traced_direct = deepgi::read_pfm(reference / "reference-direct-radiance.pfm");
        std::vector<double> relative;
        double sum_abs = 0.0, sum_truth = 0.0;
        for (int y = guard; y < truth.height - guard; ++y)
            for (int x = guard; x < truth.width - guard; ++x) {
                if (!compared(x, y)) continue;
                double a = 0.0, b = 0.0;
                for (int c = 0; c < 3; ++c) {
                    a += raster_direct.at(x, y, c);
                    b += traced_direct.at(x, y, c);
                }
                sum_abs += std::abs(a - b);
                sum_truth += b;
                if (b > 0.0) relative.push_back(std::abs(a - b) / b);
            }
        std::sort(relative.begin(), relative.end());
        const auto within = std::lower_bound(relative.begin(), relative.end(), 0.01);
        fmt::print(
            "direct light: relative difference median {:.2g}, {:.1f}% of lit pixels within "
            "1%, sum|difference| / sum = {:.4f}\n",
            relative.empty() ? 0.0 : relative[relative.size() / 2],
            relative.empty() ? 0.0
                             : 100.0 * double(within - relative.begin()) / double(relative.size()),
            sum_truth > 0.0 ? sum_abs / sum_truth : 0.0);
    }
    fmt::print(
        "reference: {} pixels, mean E {:.4f}, mean standard error {:.4f}; gather without a "
        "sample at {} pixels\n",
        count, truth_sum / n, truth_error_sum / n, empty);
    // The last row scales the filtered E by the gather's confidence. With
    // --radiosity-method published (confidence: used samples / all
    // samples) that is the gather normalised by every sample instead of
    // the used ones. With the area method E is already the integral and
    // the confidence the covered share of the hemisphere, so the row
    // means nothing there.
    struct Row {
        const char* label;
        const char* file;
        bool times_confidence;
    };
    for (const Row row :
         {Row{"radiosity-raw-layer0", "radiosity-raw-layer0", false},
          Row{"radiosity-irradiance-layer0", "radiosity-irradiance-layer0", false},
          Row{"radiosity-blurred", "radiosity-blurred", false},
          Row{"radiosity-irradiance-layer0 x confidence", "radiosity-irradiance-layer0", true}}) {
        const auto estimate = deepgi::read_pfm(dump / (std::string(row.file) + ".pfm"));
        double sum_abs = 0.0, sum = 0.0;
        for (int y = guard; y < truth.height - guard; ++y)
            for (int x = guard; x < truth.width - guard; ++x) {
                if (!compared(x, y)) continue;
                const double scale = row.times_confidence ? double(confidence.at(x, y)) : 1.0;
                for (int c = 0; c < 3; ++c) {
                    const double error = scale * double(estimate.at(x, y, c)) - truth.at(x, y, c);
                    sum_abs += std::abs(error);
                    sum += error;
                }
            }
        fmt::print("{}: MAE {:.4f}, bias {:+.4f}, relative error {:.3f}, relative bias {:+.3f}\n",
                   row.label, sum_abs / n, sum / n, truth_sum > 0.0 ? sum_abs / truth_sum : 0.0,
                   truth_sum > 0.0 ? sum / truth_sum : 0.0);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return deepgi_tools::run_tool("deepgi_compare_irradiance", argc, argv, run);
}
