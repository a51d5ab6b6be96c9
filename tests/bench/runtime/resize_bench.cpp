// What a window resize costs: Renderer::set_settings to a new size (render
// targets only) against building a new Renderer at that size (programs and
// targets, which is what every resize cost before passes kept their programs).
// Each sample ends with glFinish; medians over --repeats alternating resizes.
#include "deepgi/context.hpp"
#include "deepgi/renderer.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <vector>

using namespace deepgi;

namespace {

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

RenderSettings sized(int width, int height) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    return settings;
}

}  // namespace

int main(int argc, char** argv) {
    int repeats = 9;
    std::string scene_name = "atrium";
    CLI::App app{"deepgi resize benchmark"};
    app.add_option("--repeats", repeats, "Resizes timed per method (median reported)");
    app.add_option("--scene", scene_name);
    CLI11_PARSE(app, argc, argv);

    HeadlessContext context;
    const Scene scene = make_builtin_scene(scene_name);
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const RenderSettings sizes[2] = {sized(1280, 720), sized(1920, 1080)};
    using clock = std::chrono::steady_clock;
    auto milliseconds = [](clock::duration d) {
        return std::chrono::duration<double, std::milli>(d).count();
    };

    Renderer renderer(scene, sizes[0], loader);
    renderer.render(scene.default_camera);
    std::vector<double> resize_ms;
    std::vector<double> rebuild_ms;
    for (int i = 0; i < repeats; ++i) {
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
    const ContextInfo info = query_context_info();
    fmt::print("renderer: {}\n", info.renderer);
    fmt::print("resize between 1280x720 and 1920x1080, {} ({} repeats, median):\n", scene_name,
               repeats);
    fmt::print("  set_settings (targets only)      {:8.2f} ms\n", median(resize_ms));
    fmt::print("  new Renderer (programs + targets) {:8.2f} ms\n", median(rebuild_ms));
    fmt::print("  ratio                             {:8.1f}x\n",
               median(rebuild_ms) / median(resize_ms));
    return 0;
}
