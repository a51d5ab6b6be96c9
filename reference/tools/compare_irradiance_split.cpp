// deepgi_compare_irradiance_split DUMP_DIR REFERENCE_DIR GUARD_PIXELS LAYERS [LABEL]
// Deep radiosity's E against the part of the ray-traced one-bounce
// irradiance that its G-buffer could hold. The reference splits E by the
// layer holding the surface each sample's light leaves (E0, E1, E_neither;
// docs/reference.md); a gather over LAYERS layers can at best find E0 (one
// layer) or E0 + E1 (two): the visible truth. Over the viewport (guard band
// excluded) where the traced and the rasterised layer-0 depth agree, as
// deepgi_compare_irradiance: the share of the truth each part holds, then
// for each dumped E the relative MAE sum|E - T| / sum T and the relative bias
// sum(E - T) / sum T against the whole truth and the visible truth (channels
// summed). With LABEL, last a Markdown table row for the blurred E.
#include "deepgi/image_io.hpp"
#include "dump_frame.hpp"
#include "tool_arguments.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace {

int run(int argc, char** argv) {
    CLI::App app{
        "Deep radiosity's irradiance of a dump against the part of the ray-traced "
        "one-bounce irradiance its layers could hold (docs/reference.md)",
        "deepgi_compare_irradiance_split"};
    deepgi_tools::use_tool_layout(app);
    deepgi_tools::DumpAndReference folders;
    int layers = 2;
    std::string label;
    deepgi_tools::add_dump_and_reference(app, folders);
    const auto& [dump, reference, guard] = folders;
    app.add_option("LAYERS", layers, "The G-buffer layers the dump's gather read (1 or 2)")
        ->required()
        ->check(CLI::Range(1, 2));
    CLI::Option* label_option =
        app.add_option("LABEL", label, "With a label, last a Markdown table row for the blurred E");
    if (const auto status = deepgi_tools::parse(app, argc, argv)) return *status;
    const auto raster = deepgi::read_pfm(dump / "gbuffer-depth-layer0.pfm");
    const auto traced = deepgi::read_pfm(reference / "reference-depth-layer0.pfm");
    const auto truth = deepgi::read_pfm(reference / "reference-irradiance.pfm");
    const auto part0 = deepgi::read_pfm(reference / "reference-irradiance-layer0.pfm");
    const auto part1 = deepgi::read_pfm(reference / "reference-irradiance-layer1.pfm");
    const auto neither = deepgi::read_pfm(reference / "reference-irradiance-neither.pfm");
    for (const auto* image : {&truth, &part0, &part1, &neither})
        if (raster.width != image->width || raster.height != image->height ||
            image->channels != 3) {
            fmt::print(stderr, "size mismatch: dump {}x{}, reference {}x{}\n", raster.width,
                       raster.height, image->width, image->height);
            return 2;
        }
    auto compared = [&](int x, int y) {
        return deepgi::same_surface_depth(raster.at(x, y), traced.at(x, y));
    };
    auto visible = [&](int x, int y, int c) {
        return double(part0.at(x, y, c)) + (layers == 2 ? double(part1.at(x, y, c)) : 0.0);
    };
    double whole = 0.0, shares[3] = {0.0, 0.0, 0.0}, seen = 0.0;
    long long count = 0;
    for (int y = guard; y < truth.height - guard; ++y)
        for (int x = guard; x < truth.width - guard; ++x) {
            if (!compared(x, y)) continue;
            ++count;
            for (int c = 0; c < 3; ++c) {
                whole += truth.at(x, y, c);
                shares[0] += part0.at(x, y, c);
                shares[1] += part1.at(x, y, c);
                shares[2] += neither.at(x, y, c);
                seen += visible(x, y, c);
            }
        }
    if (!(whole > 0.0) || !(seen > 0.0)) {
        fmt::print(stderr, "no irradiance over the compared pixels\n");
        return 2;
    }
    fmt::print(
        "reference: {} pixels; share of E held by layer 0 {:.3f}, layer 1 {:.3f}, "
        "neither {:.3f}; visible truth ({}) {:.3f} of E\n",
        count, shares[0] / whole, shares[1] / whole, shares[2] / whole,
        layers == 2 ? "E0 + E1" : "E0", seen / whole);
    struct Errors {
        double mae_whole, bias_whole, mae_visible, bias_visible;
    };
    Errors blurred{};
    for (const char* file :
         {"radiosity-raw-layer0", "radiosity-irradiance-layer0", "radiosity-blurred"}) {
        const auto estimate = deepgi::read_pfm(dump / (std::string(file) + ".pfm"));
        double abs_whole = 0.0, sum_whole = 0.0, abs_visible = 0.0, sum_visible = 0.0;
        for (int y = guard; y < truth.height - guard; ++y)
            for (int x = guard; x < truth.width - guard; ++x) {
                if (!compared(x, y)) continue;
                for (int c = 0; c < 3; ++c) {
                    const double e = estimate.at(x, y, c);
                    abs_whole += std::abs(e - truth.at(x, y, c));
                    sum_whole += e - truth.at(x, y, c);
                    abs_visible += std::abs(e - visible(x, y, c));
                    sum_visible += e - visible(x, y, c);
                }
            }
        const Errors errors{abs_whole / whole, sum_whole / whole, abs_visible / seen,
                            sum_visible / seen};
        fmt::print(
            "{}: against the whole truth MAE {:.3f}, bias {:+.3f}; against the "
            "visible truth MAE {:.3f}, bias {:+.3f}\n",
            file, errors.mae_whole, errors.bias_whole, errors.mae_visible, errors.bias_visible);
        blurred = errors;
    }
    if (label_option->count() > 0)
        fmt::print(
            "| {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:+.3f} | {:.3f} | {:+.3f} "
            "|\n",
            label, layers, shares[0] / whole, shares[1] / whole, shares[2] / whole,
            blurred.mae_whole, blurred.bias_whole, blurred.mae_visible, blurred.bias_visible);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return deepgi_tools::run_tool("deepgi_compare_irradiance_split", argc, argv, run);
}
