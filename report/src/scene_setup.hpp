#pragma once
// Inside the report library: what the measurements of one scene share, the
// rows (scene_rows.cpp) and every estimator's frame-to-frame change
// (estimators.cpp), built once per scene by measure.cpp's scene loop.
#include "deepgi/report.hpp"
#include "deepgi/report_estimators.hpp"
#include "deepgi/shader_loader.hpp"

#include <functional>
#include <string>

namespace deepgi::report {

struct SceneSetup {
    const Scene& scene;
    std::string scene_name;
    RenderSettings settings;  // the report's (size, one bounce)
    const ShaderLoader& loader;
    // Writes the AO and radiosity tap headers of a pattern at n taps where
    // `loader` finds them first.
    std::function<void(const std::string& pattern, int n)> write_headers;
    // The configuration whose truth and estimate are written as images, and
    // at which every estimator's frame-to-frame change is measured.
    std::string image_pattern;
    int image_taps = 0;
    int image_layers = 0;
    SliceCost image_cost;
    // The tap count whose radiosity runs the still frames of
    // ReportOptions::radiosity_frames: the run's nearest to the renderer's.
    int radiosity_taps = 0;
    // The solid angle's tap count taken as converged: the frame-to-frame
    // change's floor row.
    int converged_taps = 0;
};

}  // namespace deepgi::report
