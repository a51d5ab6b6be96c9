#pragma once
// The report's mirror rows (docs/report.md, "Mirror reflections"): for each
// scene with mirror pixels, per layer count and reflection step count, how
// often the renderer's march finds the surface the ray-traced reflection
// hits, the error of the reflected radiance against the traced one, and the
// reflection pass's milliseconds. Scenes without mirrors give no rows.
#include "deepgi/scene.hpp"
#include "deepgi/settings.hpp"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace deepgi::report {

struct ReflectionOptions {
    bool enabled = true;  // false: no mirror rows (reflections.csv is removed)
    std::vector<int> steps = {16, 32, 64};
    // Still frames after a cut, each configuration in turn: the filtered
    // radiance is their running mean, and the timed frames are those after
    // the report's --warmup.
    int frames = 16;
};

// One scene, layer count and step count, over the viewport's mirror pixels
// where both the renderer and the reference see a mirror and their layer-0
// depths agree within 1e-3 relative.
struct ReflectionRow {
    std::string scene;
    int layers = 0;
    int steps = 0;
    int frames = 0;
    std::string device;  // GL_RENDERER
    long long mirror_pixels = 0;
    // The four shares of mirror_pixels sum to 1. Same surface: the surface the
    // renderer's hit texel stores in the layer hit is the one the traced ray
    // hits first, or both hit nothing. Renderer missed: the march found
    // nothing where the traced ray hits a surface; other surface: both hit,
    // different surfaces; renderer only: the march hit where the traced ray
    // leaves the scene.
    double same_surface = 0.0;
    double renderer_missed = 0.0;
    double other_surface = 0.0;
    double renderer_only = 0.0;
    // The filtered reflected radiance (reflection-temporal) against the
    // traced one: sum |L - L_ref| / sum L_ref and sum (L - L_ref) / sum L_ref
    // over the three channels; then the same over the same-surface pixels.
    double rel_mae = 0.0;
    double rel_bias = 0.0;
    double same_surface_rel_mae = 0.0;
    double same_surface_rel_bias = 0.0;
    // The share of mirror_pixels whose traced ray meets another mirror first,
    // and the filtered radiance's relative MAE and bias over those pixels
    // (NaN when there are none).
    double meets_mirror = 0.0;
    double meets_mirror_rel_mae = 0.0;
    double meets_mirror_rel_bias = 0.0;
    double reflection_ms = 0.0;  // median of the timed frames
};

// Throws deepgi::InputError naming the first invalid option.
void validate(const ReflectionOptions& options);

// The mirror rows of one scene: nothing for a scene without a mirror
// material or without mirror pixels in the compared viewport. `settings`
// gives the size and every setting but the reflection's layers and steps, run
// at each of `layer_counts` and options.steps;
// the reference traces with `rays` rays per hit irradiance (0: the
// reference's adaptive budget), `seed` and `threads`. Renders with the
// build's own shaders; needs a current GL context. `warmup` frames of each
// configuration are left out of its timing.
std::vector<ReflectionRow> measure_reflection_rows(
    const std::string& scene_name, const Scene& scene, const RenderSettings& settings,
    const ReflectionOptions& options, const std::vector<int>& layer_counts, int rays,
    std::uint64_t seed, int threads, int warmup,
    const std::function<void(const std::string&)>& log);

// scene,layers,steps,frames,device,mirror_pixels,same_surface,renderer_missed,
// other_surface,renderer_only,rel_mae,rel_bias,same_surface_rel_mae,
// same_surface_rel_bias,meets_mirror,meets_mirror_rel_mae,meets_mirror_rel_bias,
// reflection_ms
std::string format_reflection_csv(const std::vector<ReflectionRow>& rows);

// Writes DIR/reflections.csv, or removes it when the mirror rows are off, so
// that a table from an earlier run is not read as this one's.
void write_reflection_table(const std::filesystem::path& directory, bool enabled,
                            const std::vector<ReflectionRow>& rows);

}  // namespace deepgi::report
