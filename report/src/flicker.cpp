// Frame-to-frame change of the AO that compose uses: how much an estimator
// flickers at a still camera and along the scene's camera path
// (docs/report.md, "Frame-to-frame change").
#include "compare.hpp"
#include "deepgi/report.hpp"
#include "deepgi/report_estimators.hpp"

#include <fmt/format.h>

#include <cmath>
#include <functional>
#include <limits>

namespace deepgi::report {

ChangeFrame read_change_frame(const Renderer& renderer) {
    return {clamped_visibility(renderer.read_pass_output("ao-blurred")),
            renderer.read_pass_output("gbuffer-depth-layer0"),
            renderer.read_pass_output("gbuffer-motion-layer0")};
}

double ChangeSum::mean() const {
    return pixels > 0 ? sum / double(pixels) : std::numeric_limits<double>::quiet_NaN();
}

ChangeSum frame_change(const ChangeFrame& previous, const ChangeFrame& current, int guard) {
    const int width = current.depth.width;
    const int height = current.depth.height;
    ChangeSum change;
    for (int y = guard; y < height - guard; ++y) {
        for (int x = guard; x < width - guard; ++x) {
            const float depth = current.depth.at(x, y);
            if (!(depth > 0.0f)) continue;
            const float mx = current.motion.at(x, y, 0);
            const float my = current.motion.at(x, y, 1);
            // Rejects infinities and NaN before the conversion to int.
            if (!(std::abs(mx) < 65536.0f && std::abs(my) < 65536.0f)) continue;
            const int qx = int(std::floor(float(x) + 0.5f - mx));
            const int qy = int(std::floor(float(y) + 0.5f - my));
            if (qx < 0 || qy < 0 || qx >= width || qy >= height) continue;
            const float before = previous.depth.at(qx, qy);
            if (!(before > 0.0f) || std::abs(before - depth) > 0.05f * depth) continue;
            change.sum += std::abs(double(current.visibility.at(x, y)) -
                                   double(previous.visibility.at(qx, qy)));
            ++change.pixels;
        }
    }
    return change;
}

FlickerMeasure measure_flicker(Renderer& renderer, const Scene& scene, int frames) {
    FlickerMeasure result;
    const int guard = renderer.layout().guard;
    const int first_measured = frames / 2 + 1;
    // One sequence: frame k (from 1, a cut) at camera(k), its successor
    // camera(k + 1) given as the next camera.
    auto run = [&](const std::function<Camera(int)>& camera) {
        ChangeSum total;
        ChangeFrame previous;
        for (int k = 1; k <= frames; ++k) {
            renderer.render(camera(k), camera(k + 1),
                            k == 1 ? CameraMotion::cut : CameraMotion::continuous);
            ChangeFrame frame = read_change_frame(renderer);
            if (k >= first_measured && k > 1) {
                const ChangeSum change = frame_change(previous, frame, guard);
                total.sum += change.sum;
                total.pixels += change.pixels;
            }
            previous = std::move(frame);
        }
        return total;
    };
    result.still = run([&](int) { return scene.default_camera; });
    result.has_path = scene.camera_path.keys.size() >= 2 && scene.camera_path.frames_per_key > 0;
    if (result.has_path) {
        result.path = run([&](int k) { return camera_on_path(scene.camera_path, k - 1); });
    }
    return result;
}

std::string format_flicker_csv(const std::vector<FlickerRow>& rows) {
    std::string text =
        "scene,ao_method,role,pattern,taps,ao_slices,ao_steps,layers,frames,still_change,"
        "still_pixels,path_change,path_pixels\n";
    auto cell = [](const ChangeSum& change, bool measured) {
        if (!measured || change.pixels == 0) return std::string(",");
        return fmt::format("{},{}", change.mean(), change.pixels);
    };
    for (const FlickerRow& row : rows) {
        text += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", csv_field(row.scene),
                            csv_field(row.ao_method), row.role, csv_field(row.pattern), row.taps,
                            row.slices > 0 ? std::to_string(row.slices) : std::string(),
                            row.steps > 0 ? std::to_string(row.steps) : std::string(), row.layers,
                            row.frames, cell(row.measure.still, true),
                            cell(row.measure.path, row.measure.has_path));
    }
    return text;
}

}  // namespace deepgi::report
