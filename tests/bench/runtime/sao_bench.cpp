// sao_bench: milliseconds of the deep SAO pass against its tap count, one
// layer against two, and of the bilateral blur and the depth pyramid. Each tap
// count runs the production sao.frag with a header the codegen library writes
// for (N, optimal tau). On llvmpipe the renderer times each pass with a CPU
// clock around glFinish; on a GPU with timer queries. Medians of --frames
// frames after --warmup, all in one run. It times the solid-angle estimator
// unless told otherwise: --ao-method march times the march, whose rays and
// steps (shared_enums.h) do not follow the tap count.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/renderer.hpp"
#include "study_headers.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <regex>

namespace {

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t middle = values.size() / 2;
    return values.size() % 2 == 1 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

// Median milliseconds per pass name over `frames` frames.
std::map<std::string, double> time_frames(deepgi::Renderer& renderer, const deepgi::Camera& camera,
                                          int warmup, int frames) {
    for (int i = 0; i < warmup; ++i) renderer.render(camera);
    std::map<std::string, std::vector<double>> samples;
    for (int i = 0; i < frames; ++i) {
        renderer.render(camera);
        for (const auto& timing : renderer.last_timings())
            samples[timing.pass].push_back(timing.milliseconds);
    }
    std::map<std::string, double> medians;
    for (auto& [pass, values] : samples) medians[pass] = median(values);
    return medians;
}

}  // namespace

int main(int argc, char** argv) {
    std::string size = "1280x720";
    std::string scene_name = "cornell";
    std::vector<int> tap_counts = {4, 8, 11, 16, 32, 64};
    int warmup = 2;
    int frames = 9;
    std::string method_name{deepgi::to_string(deepgi::AoMethod::solid_angle)};
    CLI::App app{"sao_bench: deep SAO milliseconds against tap count and layers"};
    app.add_option("--size", size, "WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--scene", scene_name, "Built-in scene or glTF file")->capture_default_str();
    app.add_option("--taps", tap_counts, "Tap counts to time")->capture_default_str();
    app.add_option("--warmup", warmup, "Untimed frames first")->capture_default_str();
    app.add_option("--frames", frames, "Timed frames (the median is reported)")
        ->capture_default_str();
    app.add_option(
           "--ao-method", method_name,
           fmt::format("Deep SAO estimator: {}", deepgi::enum_name_list<deepgi::AoMethod>()))
        ->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    try {
        std::smatch match;
        static const std::regex pattern(R"(^(\d{1,5})x(\d{1,5})$)");
        if (!std::regex_match(size, match, pattern))
            throw deepgi::InputError(fmt::format("--size '{}' is not WIDTHxHEIGHT", size));
        if (frames < 1 || warmup < 0)
            throw deepgi::InputError("--frames must be >= 1 and --warmup >= 0");
        for (int n : tap_counts) {
            if (n < 1 || n > 1024)
                throw deepgi::InputError(fmt::format("--taps {} is out of range (1 to 1024)", n));
        }
        deepgi::RenderSettings settings;
        settings.width = std::stoi(match[1].str());
        settings.height = std::stoi(match[2].str());
        settings.ao.method = deepgi::parse_ao_method("--ao-method", method_name);
        settings.ao.bias = deepgi::default_ao_bias(settings.ao.method);
        const deepgi::Scene scene = deepgi::load_scene(scene_name);

        deepgi::HeadlessContext context;
        const auto info = deepgi::query_context_info();
        deepgi::study::ScratchFolder headers;
        const deepgi::ShaderLoader loader = deepgi::study::loader_with_override(headers.path());
        bool cpu_clock = false;
        fmt::print(
            "| N | tau | 1 layer (ms) | 2 layers (ms) | 2 / 1 | blur (ms) | depth pyramid (ms) "
            "|\n");
        fmt::print("|--:|--:|--:|--:|--:|--:|--:|\n");
        for (int n : tap_counts) {
            const int tau = spiral::search(n).tau;
            spiral::codegen::write_file_atomically(
                headers.path() / "ao_taps.glsl",
                spiral::codegen::make_gather_header("ao", n, tau, {"sao_bench"}));
            deepgi::Renderer renderer(scene, settings, loader);
            cpu_clock = renderer.timing_uses_cpu_clock();
            deepgi::RenderSettings one_layer = settings;
            one_layer.ao.layers = 1;
            renderer.set_settings(one_layer);
            const auto one = time_frames(renderer, scene.default_camera, warmup, frames);
            renderer.set_settings(settings);
            const auto two = time_frames(renderer, scene.default_camera, warmup, frames);
            fmt::print("| {} | {} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} |\n", n, tau,
                       one.at("sao"), two.at("sao"), two.at("sao") / one.at("sao"), two.at("blur"),
                       two.at("depth_pyramid"));
            std::fflush(stdout);
        }
        fmt::print(
            "\n{} {}x{}, scene {}, method {}, {} ({}), median of {} frames after {} "
            "warm-up frames\n",
            info.renderer, settings.width, settings.height, scene_name, method_name,
            cpu_clock ? "CPU clock around glFinish" : "GL timer queries", info.version, frames,
            warmup);
        return 0;
    } catch (const deepgi::InputError& error) {
        fmt::print(stderr, "sao_bench: error: {}\n", error.what());
        return 2;
    } catch (const std::exception& error) {
        fmt::print(stderr, "sao_bench: error: {}\n", error.what());
        return 1;
    }
}
