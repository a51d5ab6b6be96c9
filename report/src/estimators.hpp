#pragma once
// Inside the report library: the frame-to-frame change of every estimator
// on one scene (estimators.cpp), called from the scene loop of measure.cpp.
#include "scene_setup.hpp"

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace deepgi::report {

// One row per method, at the image configuration (pattern, taps, most
// layers, image_slice_cost), and one "floor" row: the solid angle at the
// converged tap count. Empty when options.flicker_frames is 0.
std::vector<FlickerRow> measure_scene_flicker(const SceneSetup& setup,
                                              std::span<const AoMethod> methods,
                                              const EstimatorOptions& options);

// measure_scene_flicker for options.ao_methods, appended to `rows`, one log
// line per row and one with the time taken.
void measure_flicker_rows(const SceneSetup& setup, const ReportOptions& options,
                          std::vector<FlickerRow>& rows,
                          const std::function<void(const std::string&)>& log);

}  // namespace deepgi::report
