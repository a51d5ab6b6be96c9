#pragma once
// Inside the report library: the rows of one scene (scene_rows.cpp), called
// from the scene loop of measure.cpp.
#include "deepgi/report.hpp"
#include "deepgi/report_estimators.hpp"
#include "deepgi/shader_loader.hpp"

#include <functional>
#include <string>

namespace deepgi::report {

struct SceneRowsSetup {
    const Scene& scene;
    std::string scene_name;
    RenderSettings settings;  // the report's (size, one bounce)
    const ShaderLoader& loader;
    // Writes the AO and radiosity tap headers of a pattern at n taps where
    // `loader` finds them first.
    std::function<void(const std::string& pattern, int n)> write_headers;
    // The configuration whose truth and estimate are written as images.
    std::string image_pattern;
    int image_taps = 0;
    int image_layers = 0;
    SliceCost image_cost;
};

// Traces the scene's truth, then renders every configuration of every
// method in options.ao_methods (ReportOptions says which) and appends one
// row each to result.rows, with one log line per row; writes the scene's
// images/<scene>-truth.pfm and images/<scene>-estimate-<method>.pfm and sets
// result.info.cpu_clock. Needs a current GL context.
void measure_scene_rows(const SceneRowsSetup& setup, const ReportOptions& options,
                        ReportResult& result, const std::function<void(const std::string&)>& log);

}  // namespace deepgi::report
