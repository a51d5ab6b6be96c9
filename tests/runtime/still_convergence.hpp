#pragma once
// How fast a still camera's blurred E and AO approach the same estimator's
// converged image (docs/radiosity.md, "How fast a still camera converges").
// One measurement shared by the benchmark that prints the docs' table
// (tests/bench/runtime/temporal_convergence.cpp) and the ctest that checks
// the targets (tests/runtime/temporal_convergence_test.cpp).
//
// Per scene and settings:
//   - the renderer renders still frames at the scene's default camera; after
//     each of `frame_counts` frames its blurred E (`radiosity-blurred`) and
//     AO (`ao-blurred`) are read;
//   - the converged image: a renderer whose radiosity gather uses
//     `converged_taps` taps (a header written at run time), after
//     `converged_frames` still frames, so its E is the running mean of that
//     many frames of a denser gather, and its AO the running mean of that
//     many frames of the same AO.
// Figures over the viewport's surface pixels: E relative RMS
// sqrt(sum (E - C)^2 / sum C^2) and relative MAE sum |E - C| / sum C; AO RMS
// of AV - C over the mean occlusion 1 - C. Fine grain: the relative RMS of a
// value minus its 9x9 box mean over pixels whose window lies on one plane of
// one albedo (E: against the value's RMS there; AO: against the mean
// occlusion), for the image and for the converged one.
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/settings.hpp"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <vector>

namespace deepgi::convergence {

// The converged image's defaults: 4x the build's 19 radiosity taps, and the
// temporal filter's running-mean cap of 256 frames.
constexpr int default_converged_taps = 76;
constexpr int default_converged_frames = 256;

struct StillFigures {
    int frames = 0;
    double e_rms = 0.0;     // relative RMS of blurred E against the converged E
    double e_mae = 0.0;     // relative MAE of the same
    double e_grain = 0.0;   // fine grain of the image's E
    double ao_rms = 0.0;    // RMS of AV - C over the mean occlusion 1 - C
    double ao_grain = 0.0;  // fine grain of the image's AO
};

struct StillConvergence {
    std::vector<StillFigures> rows;  // one per frame count, in the given order
    double converged_e_grain = 0.0;
    double converged_ao_grain = 0.0;
    std::size_t flat_pixels = 0;  // pixels the fine grain is taken over
    std::size_t pixels = 0;       // the viewport's pixels
};

// Optional looks into a run, each called when set (the benchmark's --maps
// and --check-running-mean); images are of the viewport's size.
struct StillObserver {
    // Once, with the converged image's blurred AO and layer 0's depth.
    std::function<void(const FloatImage& converged_ao, const FloatImage& depth)> converged;
    // Once, with the renderer of the converged image after its last frame.
    std::function<void(const Renderer& dense)> converged_renderer;
    // After each still frame of the measured renderer.
    std::function<void(const Renderer&)> frame;
    // At each frame count, with the image's blurred AO.
    std::function<void(const Renderer&, int frames, const FloatImage& ao)> count;
};

// Needs a current GL context. `frame_counts` must be increasing and >= 1;
// the renderers are the build's (plus the converged image's tap header).
// `shaders`, when not empty, is searched first by both renderers, as
// `deepgi --shaders` searches it: a folder of edited copies, so that a
// variant is measured against its own converged image without editing the
// source tree.
StillConvergence measure_still_convergence(const Scene& scene, const RenderSettings& settings,
                                           const std::vector<int>& frame_counts,
                                           int converged_taps = default_converged_taps,
                                           int converged_frames = default_converged_frames,
                                           const StillObserver& observer = {},
                                           const std::filesystem::path& shaders = {});

// The viewport part of an internal-size image (the guard band cut off), or
// the image itself when it already has the viewport's size.
FloatImage viewport_of(const FloatImage& image, int width, int height);

}  // namespace deepgi::convergence
