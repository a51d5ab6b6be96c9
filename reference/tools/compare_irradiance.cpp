// deepgi_compare_irradiance DUMP_DIR REFERENCE_DIR GUARD_PIXELS
// Compares deep radiosity's layer-0 irradiance from `deepgi --headless --dump`
// against the ray-traced one-bounce irradiance of `deepgi reference` on the
// same scene, size and guard band, over the viewport (guard band excluded)
// where the traced and the rasterised layer-0 depth agree. For each dumped
// image (one frame's raw gather, the temporally filtered E, the blurred E):
// mean absolute error, bias and the relative error sum|E - E_ref| / sum E_ref,
// averaged over the three channels; also the share of pixels the gather left
// without a sample (confidence 0).
#include "deepgi/image_io.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <string>

int main(int argc, char** argv) {
    if (argc != 4) {
        fmt::print(stderr,
                   "usage: deepgi_compare_irradiance DUMP_DIR REFERENCE_DIR GUARD_PIXELS\n");
        return 2;
    }
    try {
        const std::filesystem::path dump = argv[1], reference = argv[2];
        const int guard = std::stoi(argv[3]);
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
            const float a = raster.at(x, y), b = traced.at(x, y);
            return a > 0.0f && b > 0.0f && std::abs(a - b) <= 1e-3f * b;
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
        fmt::print(
            "reference: {} pixels, mean E {:.4f}, mean standard error {:.4f}; gather without a "
            "sample at {} pixels\n",
            count, truth_sum / n, truth_error_sum / n, empty);
        for (const char* name :
             {"radiosity-raw-layer0", "radiosity-irradiance-layer0", "radiosity-blurred"}) {
            const auto estimate = deepgi::read_pfm(dump / (std::string(name) + ".pfm"));
            double sum_abs = 0.0, sum = 0.0;
            for (int y = guard; y < truth.height - guard; ++y)
                for (int x = guard; x < truth.width - guard; ++x) {
                    if (!compared(x, y)) continue;
                    for (int c = 0; c < 3; ++c) {
                        const double error = double(estimate.at(x, y, c)) - truth.at(x, y, c);
                        sum_abs += std::abs(error);
                        sum += error;
                    }
                }
            fmt::print(
                "{}: MAE {:.4f}, bias {:+.4f}, relative error {:.3f}, relative bias {:+.3f}\n",
                name, sum_abs / n, sum / n, truth_sum > 0.0 ? sum_abs / truth_sum : 0.0,
                truth_sum > 0.0 ? sum / truth_sum : 0.0);
        }
    } catch (const std::exception& error) {
        fmt::print(stderr, "deepgi_compare_irradiance: {}\n", error.what());
        return 2;
    }
    return 0;
}
