// reflection_bench: what the mirror reflections cost per frame, in one run.
//
// Per scene (default gallery, the built-in scene with a mirror floor), one
// renderer per layer count (1, 2) and step count (--steps, default 16, 32,
// 64), plus the single-pass generators (previous, reproject, predict, delay)
// at the default reflection settings for the G-buffer milliseconds of each
// generator; peel's are those of the 2-layer, 32-step renderer. The camera
// stands still, so delay's next camera is this one and predict's
// extrapolation is exact; what a generator costs does not depend on that. All take turns frame by
// frame (bench_harness.hpp); every pass is timed with a CPU clock around glFinish
// (--timing gpu for GL timer queries on a GPU); medians of --frames frames
// after --warmup frames under the scene's default camera.
#include "bench_harness.hpp"
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "passes/passes.hpp"

#include <fmt/format.h>

#include <iterator>
#include <memory>

namespace {

constexpr deepgi::Generator single_pass[] = {deepgi::Generator::previous,
                                             deepgi::Generator::reproject,
                                             deepgi::Generator::predict, deepgi::Generator::delay};

}  // namespace

int main(int argc, char** argv) {
    deepgi::bench::Options options;
    options.scenes = {"gallery"};
    std::vector<int> steps = {16, 32, 64};
    CLI::App app{
        "reflection_bench: mirror reflection milliseconds, one layer against two, per "
        "step count; G-buffer milliseconds per generator"};
    deepgi::bench::add_options(app, options);
    app.add_option("--steps", steps, "Reflection step counts")->delimiter(',');
    CLI11_PARSE(app, argc, argv);
    return deepgi::bench::run("reflection_bench", [&] {
        deepgi::bench::finish(options);
        const deepgi::RenderSettings settings = deepgi::bench::settings_for(options);
        deepgi::validate(settings);
        for (int count : steps) {
            deepgi::RenderSettings check = settings;
            check.reflection.steps = count;
            deepgi::validate(check);
        }
        deepgi::HeadlessContext context;
        const deepgi::ShaderLoader loader = deepgi::ShaderLoader::from_build_configuration();
        std::string measured;
        std::vector<std::string> generator_rows;
        fmt::print(
            "| scene | steps | reflection, 1 layer (ms) | reflection, 2 layers (ms) | 2 / 1 "
            "| frame, 2 layers (ms) |\n|---|---|---|---|---|---|\n");
        for (const auto& name : options.scenes) {
            const deepgi::Scene scene = deepgi::load_scene(name);
            if (!deepgi::reflections_traced(scene, settings))
                throw deepgi::InputError(
                    fmt::format("--scenes: '{}' has no mirror material to reflect in", name));
            std::vector<std::unique_ptr<deepgi::Renderer>> renderers;
            std::vector<deepgi::bench::Configuration> configurations;
            auto add = [&](const deepgi::RenderSettings& s) {
                renderers.push_back(std::make_unique<deepgi::Renderer>(scene, s, loader));
                configurations.push_back({renderers.back().get(), scene.default_camera});
            };
            for (int count : steps) {
                for (int layers : {1, 2}) {
                    deepgi::RenderSettings s = settings;
                    s.reflection.steps = count;
                    s.reflection.layers = layers;
                    add(s);
                }
            }
            for (deepgi::Generator generator : single_pass) {
                deepgi::RenderSettings s = settings;
                s.generator = generator;
                add(s);
            }
            const auto medians = deepgi::bench::time_alternated(configurations, options);
            if (measured.empty())
                measured = deepgi::bench::measured_on(*renderers.front(), options);
            // Peel's G-buffer: the 2-layer renderer at the default step count
            // (or at the first step count when the default is not among them).
            std::size_t peel = 1;
            for (std::size_t i = 0; i < steps.size(); ++i) {
                const auto& one = medians[2 * i];
                const auto& two = medians[2 * i + 1];
                if (steps[i] == deepgi::ReflectionSettings{}.steps) peel = 2 * i + 1;
                fmt::print("| {} | {} | {:.2f} | {:.2f} | {:.2f} | {:.1f} |\n", name, steps[i],
                           one.at("reflection"), two.at("reflection"),
                           two.at("reflection") / one.at("reflection"), two.at("total"));
            }
            std::fflush(stdout);
            const std::size_t generators = 2 * steps.size();
            generator_rows.push_back(fmt::format("| {} | peel | {:.2f} | {:.1f} |", name,
                                                 medians[peel].at("gbuffer"),
                                                 medians[peel].at("total")));
            for (std::size_t g = 0; g < std::size(single_pass); ++g) {
                const auto& m = medians[generators + g];
                generator_rows.push_back(fmt::format("| {} | {} | {:.2f} | {:.1f} |", name,
                                                     deepgi::to_string(single_pass[g]),
                                                     m.at("gbuffer"), m.at("total")));
            }
        }
        fmt::print(
            "\nG-buffer per generator (peel: the 2-layer renderer at the default step "
            "count):\n\n| scene | generator | gbuffer (ms) | frame (ms) |\n|---|---|---|---|\n");
        for (const auto& row : generator_rows) fmt::print("{}\n", row);
        fmt::print("\n{}\n", measured);
        return 0;
    });
}
