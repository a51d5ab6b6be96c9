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
// Prints one line of key=value pairs. The counting is the reference
// library's compare_reflection_images (deepgi/reflection_comparison.hpp),
// which the report's mirror rows count with too.
#include "deepgi/image_io.hpp"
#include "deepgi/reflection_comparison.hpp"
#include "tool_arguments.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <string>

namespace {

int run(int argc, char** argv) {
    CLI::App app{
        "The reflection pass of a dump against the traced mirror reflections (docs/reflections.md)",
        "deepgi_compare_reflections"};
    deepgi_tools::use_tool_layout(app);
    deepgi_tools::DumpAndReference folders;
    deepgi_tools::add_dump_and_reference(app, folders);
    const auto& [dump, reference, guard] = folders;
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
    // A dump that does not fit the reference throws: one line, exit status 2.
    const deepgi::ReflectionComparison r = deepgi::compare_reflection_images(
        {raster, hit, radiance, filtered, traced, truth, truth_hit, layers}, guard);
    const double n = std::max(r.mirror_pixels, 1LL);
    const double sum = std::max(r.radiance.truth, 1e-30);
    const double same_truth = std::max(r.same_surface_filtered.truth, 1e-30);
    fmt::print(
        "mirror_pixels={} same_surface={:.4f} both_miss={:.4f} renderer_missed={:.4f} "
        "wrong_surface={:.4f} renderer_only={:.4f} mean_truth={:.4g} rel_mae={:.4f} "
        "rel_bias={:+.4f} filtered_rel_mae={:.4f} filtered_rel_bias={:+.4f} "
        "same_surface_filtered_rel_mae={:.4f} same_surface_filtered_rel_bias={:+.4f}\n",
        r.mirror_pixels, r.same_surface / n, r.both_miss / n, r.renderer_missed / n,
        r.wrong_surface / n, r.renderer_only / n, r.radiance.truth / (3.0 * n),
        r.radiance.absolute_error / sum, r.radiance.error / sum, r.filtered.absolute_error / sum,
        r.filtered.error / sum, r.same_surface_filtered.absolute_error / same_truth,
        r.same_surface_filtered.error / same_truth);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return deepgi_tools::run_tool("deepgi_compare_reflections", argc, argv, run);
}
