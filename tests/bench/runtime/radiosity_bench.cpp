// radiosity_bench: what deep radiosity costs per frame, in one run.
//
// Per scene, two renderers at the same size: the default frame (every pass
// on, two radiosity layers, the AO and the radiosity E through one shared
// bilateral blur), and the same with one radiosity layer (the paper's 1-vs-2
// layer ratio).
// Every pass is timed with a CPU clock around glFinish (--timing gpu for GL
// timer queries on a GPU); medians of --frames frames after --warmup frames
// under the scene's default (static) camera, the two renderers taking turns
// frame by frame.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/renderer.hpp"
#include "pass.hpp"
#include "passes/passes.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <regex>

namespace {

using Medians = std::map<std::string, double>;

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t middle = values.size() / 2;
    return values.size() % 2 == 1 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

// Renders the scene's default camera with each renderer in turn, frame by
// frame (so a change in machine load hits all of them alike), and returns
// each one's median ms per pass, "total" being the median of the per-frame
// sums. `order` receives the pass names of the first renderer in run order.
std::vector<Medians> time_interleaved(const deepgi::Scene& scene,
                                      const std::vector<deepgi::RenderSettings>& configurations,
                                      int warmup, int frames, std::vector<std::string>& order) {
    std::vector<std::unique_ptr<deepgi::Renderer>> renderers;
    for (const auto& settings : configurations)
        renderers.push_back(std::make_unique<deepgi::Renderer>(
            scene, settings, deepgi::ShaderLoader::from_build_configuration()));
    std::vector<std::map<std::string, std::vector<double>>> samples(renderers.size());
    for (int i = 0; i < warmup + frames; ++i) {
        for (std::size_t r = 0; r < renderers.size(); ++r) {
            renderers[r]->render(scene.default_camera);
            if (i < warmup) continue;
            double total = 0.0;
            for (const auto& timing : renderers[r]->last_timings()) {
                if (r == 0 && i == warmup) order.push_back(timing.pass);
                samples[r][timing.pass].push_back(timing.milliseconds);
                total += timing.milliseconds;
            }
            samples[r]["total"].push_back(total);
        }
    }
    std::vector<Medians> medians(renderers.size());
    for (std::size_t r = 0; r < renderers.size(); ++r)
        for (auto& [pass, values] : samples[r]) medians[r][pass] = median(values);
    return medians;
}

}  // namespace

int main(int argc, char** argv) {
    std::string size = "1280x720";
    std::vector<std::string> scenes = {"cornell", "atrium", "warehouse"};
    int warmup = 1;
    int frames = 3;
    std::string timing = "cpu";
    CLI::App app{"radiosity_bench: deep radiosity milliseconds, 1 vs 2 layers, shared blur"};
    app.add_option("--size", size, "WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--scenes", scenes, "Built-in scenes or glTF files")->capture_default_str();
    app.add_option("--warmup", warmup, "Untimed frames first")->capture_default_str();
    app.add_option("--frames", frames, "Timed frames (the median is reported)")
        ->capture_default_str();
    app.add_option("--timing", timing, "cpu (clock around glFinish) or gpu (timer queries)")
        ->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    try {
        std::smatch match;
        if (!std::regex_match(size, match, std::regex(R"((\d{1,5})x(\d{1,5}))")))
            throw deepgi::InputError(fmt::format("--size '{}' is not WIDTHxHEIGHT", size));
        if (frames < 1 || warmup < 0)
            throw deepgi::InputError("--frames must be at least 1 and --warmup at least 0");
        deepgi::RenderSettings settings;
        settings.width = std::stoi(match[1].str());
        settings.height = std::stoi(match[2].str());
        settings.timing = deepgi::parse_timing_mode("--timing", timing);
        deepgi::validate(settings);

        deepgi::HeadlessContext context;
        const auto info = deepgi::query_context_info();
        fmt::print("{} | {} | {}x{} | median of {} frames after {} warm-up frames\n\n",
                   info.renderer, info.version, settings.width, settings.height, frames, warmup);

        std::vector<std::string> order;
        std::vector<std::pair<std::string, Medians>> full_frames;
        fmt::print(
            "| scene | radiosity, 1 layer (ms) | radiosity, 2 layers (ms) | 2 / 1 | blur (ms) | "
            "frame, 1 layer (ms) | frame, 2 layers (ms) |\n"
            "|---|---|---|---|---|---|---|\n");
        for (const auto& name : scenes) {
            const deepgi::Scene scene = deepgi::load_scene(name);
            std::vector<std::string> scene_order;
            deepgi::RenderSettings one_layer = settings;
            one_layer.radiosity.layers = 1;
            const std::vector<Medians> medians =
                time_interleaved(scene, {settings, one_layer}, warmup, frames, scene_order);
            const Medians& two = medians[0];
            const Medians& one = medians[1];
            fmt::print("| {} | {:.1f} | {:.1f} | {:.2f} | {:.1f} | {:.1f} | {:.1f} |\n", name,
                       one.at("radiosity"), two.at("radiosity"),
                       two.at("radiosity") / one.at("radiosity"), two.at("blur"), one.at("total"),
                       two.at("total"));
            std::fflush(stdout);
            if (order.empty()) order = scene_order;
            full_frames.emplace_back(name, two);
        }

        fmt::print("\nPer pass, default frame (ms):\n\n| scene |");
        for (const auto& pass : order) fmt::print(" {} |", pass);
        fmt::print(" total |\n|---|");
        for (std::size_t i = 0; i <= order.size(); ++i) fmt::print("---|");
        fmt::print("\n");
        for (const auto& [name, medians] : full_frames) {
            fmt::print("| {} |", name);
            for (const auto& pass : order) {
                const auto found = medians.find(pass);
                if (found == medians.end())
                    fmt::print(" - |");
                else
                    fmt::print(" {:.1f} |", found->second);
            }
            fmt::print(" {:.1f} |\n", medians.at("total"));
        }
        return 0;
    } catch (const deepgi::InputError& error) {
        fmt::print(stderr, "radiosity_bench: error: {}\n", error.what());
        return 2;
    } catch (const std::exception& error) {
        fmt::print(stderr, "radiosity_bench: error: {}\n", error.what());
        return 1;
    }
}
