#pragma once
// Inside the report library: the rows of one scene (scene_rows.cpp), called
// from the scene loop of measure.cpp.
#include "scene_setup.hpp"

#include <functional>
#include <string>

namespace deepgi::report {

// Traces the scene's truth, then renders every configuration of every
// method in options.ao_methods (ReportOptions says which) and appends one
// row each to result.rows, with one log line per row; writes the scene's
// images/<scene>-truth.pfm and images/<scene>-estimate-<method>.pfm and sets
// result.info.cpu_clock. Needs a current GL context.
void measure_scene_rows(const SceneSetup& setup, const ReportOptions& options, ReportResult& result,
                        const std::function<void(const std::string&)>& log);

}  // namespace deepgi::report
