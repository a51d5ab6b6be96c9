#pragma once
// Every deep SAO estimator on the report's scenes, at several costs, and how
// much each one's image changes from frame to frame (docs/report.md,
// "Estimators at several costs" and "Frame-to-frame change").
#include "deepgi/image_io.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/settings.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace deepgi::report {

// One cost of the slice estimators (gtao, bitmask): `--ao-slices` x `--ao-steps`.
struct SliceCost {
    int slices = 2;
    int steps = 8;
    friend bool operator==(const SliceCost&, const SliceCost&) = default;
};

// "SxK" (e.g. "2x8"); throws deepgi::InputError naming `option` otherwise or
// when S or K is outside the settings rows' limits.
SliceCost parse_slice_cost(std::string_view option, std::string_view text);

struct EstimatorOptions {
    // The costs gtao and bitmask run at; each is a point of their curve.
    std::vector<SliceCost> slice_costs = {{1, 4}, {2, 8}, {4, 8}};
    // Frames of the still and of the path sequence whose frame-to-frame
    // change flicker.csv holds; the second half of each is measured. 0 skips
    // them.
    int flicker_frames = 16;
};

// Throws deepgi::InputError naming the first invalid option.
void validate(const EstimatorOptions& options);

// The cost the per-scene images, the estimator table and the flicker rows
// use for gtao and bitmask: the renderer's default (2x8) where it is listed,
// else the first listed.
SliceCost image_slice_cost(const EstimatorOptions& options);

// ---------------------------------------------------------------------------
// Frame-to-frame change

// What one frame gives the measure, at the internal size (guard band
// included), as Renderer::read_pass_output decodes them.
struct ChangeFrame {
    FloatImage visibility;  // ao-blurred clamped to [0, 1]: what compose multiplies by
    FloatImage depth;       // gbuffer-depth-layer0, metres, 0 where no surface
    FloatImage motion;      // gbuffer-motion-layer0: pixels moved since last frame (R, G)
};
ChangeFrame read_change_frame(const Renderer& renderer);

struct ChangeSum {
    double sum = 0.0;  // of |AV_t(p) - AV_{t-1}(q)|
    long long pixels = 0;
    double mean() const;  // NaN for no pixel
};

// Over the viewport pixels p of `current` that hold a surface and whose point
// the previous frame saw: q = floor(p + 1/2 - motion) inside the image, with
// a surface whose depth is within 5% of p's (the temporal filters' tolerance,
// shaders/history_reprojection.glsl; a path step moves the camera far less
// than 5% of the depth, a disocclusion jumps much further). With a still
// camera q = p.
ChangeSum frame_change(const ChangeFrame& previous, const ChangeFrame& current, int guard);

struct FlickerMeasure {
    ChangeSum still;        // frames F/2 + 1 .. F after a cut at the default camera
    ChangeSum path;         // frames F/2 + 1 .. F of the camera path from its step 0
    bool has_path = false;  // the scene's path has at least two keys
};

// Renders `frames` (F) frames at the scene's default camera, the first a cut,
// then F frames along its camera path (step k - 1 at frame k, the next step
// given as the next camera, the first a cut), and sums frame_change over
// frames F/2 + 1 .. F of each (F/2 rounded down).
FlickerMeasure measure_flicker(Renderer& renderer, const Scene& scene, int frames);

struct FlickerRow {
    std::string scene;
    std::string ao_method;
    // "estimator", or "floor": the solid angle at the converged tap count,
    // whose own sampling noise is small, so its change along the path is
    // mostly the true change of the image and the reprojection's resampling.
    std::string role;
    std::string pattern;
    int taps = 0;
    int slices = 0;  // 0 for an estimator without slices
    int steps = 0;
    int layers = 0;
    int frames = 0;
    FlickerMeasure measure;
};

// scene,ao_method,role,pattern,taps,ao_slices,ao_steps,layers,frames,
// still_change,still_pixels,path_change,path_pixels (empty cells where the
// scene has no path or no pixel was compared).
std::string format_flicker_csv(const std::vector<FlickerRow>& rows);

}  // namespace deepgi::report
