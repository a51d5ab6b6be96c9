// deepgi_bench: per-pass milliseconds of the default frame for every scene
// and G-buffer generator. The three generators of a scene take turns frame by
// frame (bench_harness.hpp); one Markdown table per scene, one row per
// generator, one column per pass the frame timed.
#include "bench_harness.hpp"
#include "deepgi/context.hpp"

#include <fmt/format.h>

#include <memory>

using namespace deepgi;

int main(int argc, char** argv) {
    bench::Options options;
    options.scenes = builtin_scene_names();
    CLI::App app{"deepgi_bench: per-pass milliseconds per scene and G-buffer generator"};
    bench::add_options(app, options);
    CLI11_PARSE(app, argc, argv);
    return bench::run("deepgi_bench", [&] {
        bench::finish(options);
        HeadlessContext context;
        const Generator generators[] = {Generator::peel, Generator::previous, Generator::reproject};
        for (const auto& scene_name : options.scenes) {
            const Scene scene = load_scene(scene_name);
            std::vector<std::unique_ptr<Renderer>> renderers;
            std::vector<bench::Configuration> configurations;
            for (Generator generator : generators) {
                RenderSettings settings = bench::settings_for(options);
                settings.generator = generator;
                renderers.push_back(std::make_unique<Renderer>(
                    scene, settings, ShaderLoader::from_build_configuration()));
                configurations.push_back({renderers.back().get(), scene.default_camera});
            }
            const auto medians = bench::time_alternated(configurations, options);
            std::vector<std::string> passes;
            for (const auto& timing : renderers.front()->last_timings())
                passes.push_back(timing.pass);
            passes.push_back("total");
            fmt::print("\n{}, {}\n\n| scene | generator |", scene_name,
                       bench::measured_on(*renderers.front(), options));
            for (const auto& pass : passes) fmt::print(" {} |", pass);
            fmt::print("\n|---|---|");
            for (std::size_t i = 0; i < passes.size(); ++i) fmt::print("--:|");
            fmt::print("\n");
            for (std::size_t g = 0; g < configurations.size(); ++g) {
                fmt::print("| {} | {} |", scene_name, to_string(generators[g]));
                for (const auto& pass : passes) {
                    const auto found = medians[g].find(pass);
                    // A pass a generator does not run shows as "-", never as 0.
                    if (found == medians[g].end())
                        fmt::print(" - |");
                    else
                        fmt::print(" {:.2f} |", found->second);
                }
                fmt::print("\n");
            }
        }
        return 0;
    });
}
