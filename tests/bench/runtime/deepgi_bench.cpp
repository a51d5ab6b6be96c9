// Per-pass milliseconds of the deepgi frame for every built-in scene and
// G-buffer generator. Medians over --frames timed frames after two warm-up
// frames (so the single-pass generators have a previous frame). On llvmpipe
// each pass is bracketed by glFinish and a CPU clock; on a GPU, timer queries.
#include "deepgi/context.hpp"
#include "deepgi/renderer.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <vector>

using namespace deepgi;

int main(int argc, char** argv) {
    int width = 1280;
    int height = 720;
    int frames = 7;
    std::vector<std::string> scenes = builtin_scene_names();
    CLI::App app{"deepgi per-pass benchmark"};
    app.add_option("--width", width);
    app.add_option("--height", height);
    app.add_option("--frames", frames, "Timed frames per configuration (median reported)");
    app.add_option("--scenes", scenes);
    CLI11_PARSE(app, argc, argv);

    HeadlessContext context;
    const ContextInfo info = query_context_info();
    fmt::print("device: {} | {}x{} | median of {} frames after 2 warm-up frames\n", info.renderer,
               width, height, frames);
    for (const auto& scene_name : scenes) {
        const Scene scene = make_builtin_scene(scene_name);
        for (Generator generator : {Generator::peel, Generator::previous, Generator::reproject}) {
            RenderSettings settings;
            settings.width = width;
            settings.height = height;
            settings.generator = generator;
            Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
            std::map<std::string, std::vector<double>> samples;
            std::vector<std::string> order;
            for (int frame = 0; frame < frames + 2; ++frame) {
                renderer.render(scene.default_camera);
                if (frame < 2) continue;
                double total = 0.0;
                for (const auto& timing : renderer.last_timings()) {
                    if (!samples.count(timing.pass)) order.push_back(timing.pass);
                    samples[timing.pass].push_back(timing.milliseconds);
                    total += timing.milliseconds;
                }
                if (!samples.count("total")) order.push_back("total");
                samples["total"].push_back(total);
            }
            std::string line =
                fmt::format("{:<10} {:<10} ({})", scene_name, to_string(generator),
                            renderer.timing_uses_cpu_clock() ? "cpu clock" : "timer queries");
            for (const auto& pass : order) {
                auto& values = samples[pass];
                std::sort(values.begin(), values.end());
                line += fmt::format(" | {} {:.2f}", pass, values[values.size() / 2]);
            }
            fmt::print("{} ms\n", line);
        }
    }
    return 0;
}
