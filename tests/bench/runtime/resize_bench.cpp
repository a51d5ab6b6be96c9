// What a window resize costs: Renderer::set_settings to a new size (render
// targets only) against building a new Renderer at that size (programs and
// targets, which is what every resize cost before passes kept their programs).
// Each sample ends with glFinish and is timed with a CPU clock (a resize is
// host work; --timing has nothing to time); medians over --frames resizes
// alternating between --size and 1.5 times it, per scene of --scenes.
#include "bench_harness.hpp"
#include "deepgi/context.hpp"

#include <fmt/format.h>

#include <chrono>

using namespace deepgi;

int main(int argc, char** argv) {
    bench::Options options;
    options.scenes = {"atrium"};
    options.frames = 9;
    CLI::App app{"resize_bench: set_settings to a new size against a new Renderer"};
    bench::add_options(app, options);
    CLI11_PARSE(app, argc, argv);
    return bench::run("resize_bench", [&] {
        bench::finish(options);
        HeadlessContext context;
        const ShaderLoader loader = ShaderLoader::from_build_configuration();
        RenderSettings sizes[2] = {bench::settings_for(options), bench::settings_for(options)};
        sizes[1].width = std::max(1, options.width * 3 / 2);
        sizes[1].height = std::max(1, options.height * 3 / 2);
        validate(sizes[1]);
        using clock = std::chrono::steady_clock;
        auto milliseconds = [](clock::duration d) {
            return std::chrono::duration<double, std::milli>(d).count();
        };
        fmt::print(
            "| scene | set_settings, targets only (ms) | new Renderer, programs + targets "
            "(ms) | ratio |\n|---|--:|--:|--:|\n");
        std::string measured;
        for (const auto& scene_name : options.scenes) {
            const Scene scene = load_scene(scene_name);
            Renderer renderer(scene, sizes[0], loader);
            for (int i = 0; i < options.warmup; ++i) renderer.render(scene.default_camera);
            std::vector<double> resize_ms;
            std::vector<double> rebuild_ms;
            for (int i = 0; i < options.frames; ++i) {
                const RenderSettings& target = sizes[(i + 1) % 2];
                glFinish();
                auto start = clock::now();
                renderer.set_settings(target);
                glFinish();
                resize_ms.push_back(milliseconds(clock::now() - start));

                start = clock::now();
                {
                    Renderer fresh(scene, target, loader);
                    glFinish();
                    rebuild_ms.push_back(milliseconds(clock::now() - start));
                }
            }
            const double resize = bench::median(resize_ms);
            const double rebuild = bench::median(rebuild_ms);
            fmt::print("| {} | {:.2f} | {:.2f} | {:.1f} |\n", scene_name, resize, rebuild,
                       rebuild / resize);
            if (measured.empty()) measured = bench::measured_on(renderer, options);
        }
        fmt::print("\n{}; resizes between {}x{} and {}x{}\n", measured, sizes[0].width,
                   sizes[0].height, sizes[1].width, sizes[1].height);
        return 0;
    });
}
