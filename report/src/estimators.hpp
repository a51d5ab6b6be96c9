#pragma once
// Inside the report library: the frame-to-frame change of every estimator
// on one scene (estimators.cpp), called from the scene loop of measure.cpp.
#include "deepgi/report.hpp"
#include "deepgi/report_estimators.hpp"
#include "deepgi/shader_loader.hpp"

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace deepgi::report {

struct FlickerSetup {
    const Scene& scene;
    std::string scene_name;
    RenderSettings settings;  // the report's (size, one bounce)
    const ShaderLoader& loader;
    // Writes the AO and radiosity tap headers of a pattern at n taps where
    // `loader` finds them first.
    std::function<void(const std::string& pattern, int n)> write_headers;
    std::string image_pattern;
    int image_taps = 0;
    int image_layers = 0;
    int converged_taps = 0;
};

// One row per method, at the image configuration (pattern, taps, most
// layers, image_slice_cost), and one "floor" row: the solid angle at the
// converged tap count. Empty when options.flicker_frames is 0.
std::vector<FlickerRow> measure_scene_flicker(const FlickerSetup& setup,
                                              std::span<const AoMethod> methods,
                                              const EstimatorOptions& options);

// measure_scene_flicker for options.ao_methods, appended to `rows`, one log
// line per row and one with the time taken.
void measure_flicker_rows(const FlickerSetup& setup, const ReportOptions& options,
                          std::vector<FlickerRow>& rows,
                          const std::function<void(const std::string&)>& log);

}  // namespace deepgi::report
