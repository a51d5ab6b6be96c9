// sao_bench: milliseconds of the deep SAO pass against its tap count, one
// layer against two, and of the bilateral blur and the depth pyramid. Each tap
// count runs the production sao.frag with a header the codegen library writes
// for (N, optimal tau). On llvmpipe the renderer times each pass with a CPU
// clock around glFinish (--timing cpu); on a GPU with timer queries (--timing
// gpu). Medians of --frames frames after --warmup, one layer and two taking
// turns frame by frame, every scene of --scenes in one run. It times the solid-angle estimator
// unless told otherwise: --ao-method march times the march, whose rays and
// steps (shared_enums.h) do not follow the tap count. --against M adds a
// third renderer, two layers with estimator M, to the same alternation, and
// the ratio of the two estimators' SAO passes (one run, frame by frame), and
// for both the depth pyramid and the passes that read it besides SAO
// (ao_temporal, radiosity, blur; the thick spiral's pyramid is RGBA32F, the
// solid angle's and the slice estimators' RG32F), and the normal pair pass
// that runs for the march, the thick spiral and the solid angle, with the
// ratio of each one's SAO plus its normal pair.
// --ao-slices / --ao-steps set the slice estimators' (gtao, bitmask) counts,
// which the tap count does not change either. --baseline-shaders DIR times,
// in place of one layer, the same two-layer estimator built from the shader
// sources in DIR (a copy of shaders/ before a change): the before and after of
// a shader change, alternated in one run.
#include "bench_harness.hpp"
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "study_headers.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <optional>
#include <vector>

int main(int argc, char** argv) {
    deepgi::bench::Options options;
    options.scenes = {"cornell"};
    options.frames = 9;
    std::vector<int> tap_counts = {4, 8, 11, 16, 32, 64};
    std::string method_name{deepgi::to_string(deepgi::AoMethod::solid_angle)};
    CLI::App app{"sao_bench: deep SAO milliseconds against tap count and layers"};
    deepgi::bench::add_options(app, options);
    app.add_option("--taps", tap_counts, "Tap counts to time, comma-separated")
        ->delimiter(',')
        ->capture_default_str();
    app.add_option(
           "--ao-method", method_name,
           fmt::format("Deep SAO estimator: {}", deepgi::enum_name_list<deepgi::AoMethod>()))
        ->capture_default_str();
    std::string against_name;
    app.add_option("--against", against_name,
                   "Also time this estimator (two layers) in the same alternation, and print the "
                   "ratio of the SAO passes");
    deepgi::AoSettings defaults;
    int slices = defaults.slices;
    int steps = defaults.steps;
    app.add_option("--ao-slices", slices, "gtao and bitmask: slices per pixel")
        ->capture_default_str();
    app.add_option("--ao-steps", steps, "gtao and bitmask: samples per slice side")
        ->capture_default_str();
    std::string baseline_dir;
    app.add_option("--baseline-shaders", baseline_dir,
                   "Time the two-layer estimator built from the shader sources in this folder in "
                   "place of one layer (before and after a shader change, in one alternation)");
    CLI11_PARSE(app, argc, argv);

    return deepgi::bench::run("sao_bench", [&] {
        deepgi::bench::finish(options);
        for (int n : tap_counts) {
            if (n < 1 || n > 1024)
                throw deepgi::InputError(fmt::format("--taps {} is out of range (1 to 1024)", n));
        }
        if (slices < 1 || slices > deepgi::limits::max_ao_slices)
            throw deepgi::InputError(fmt::format("--ao-slices {} is out of range (1 to {})", slices,
                                                 deepgi::limits::max_ao_slices));
        if (steps < 1 || steps > deepgi::limits::max_ao_steps)
            throw deepgi::InputError(fmt::format("--ao-steps {} is out of range (1 to {})", steps,
                                                 deepgi::limits::max_ao_steps));
        deepgi::RenderSettings settings = deepgi::bench::settings_for(options);
        settings.ao.slices = slices;
        settings.ao.steps = steps;
        settings.ao.method = deepgi::parse_ao_method("--ao-method", method_name);
        settings.ao.bias = deepgi::default_ao_bias(settings.ao.method);
        deepgi::RenderSettings one_layer = settings;
        one_layer.ao.layers = 1;
        deepgi::RenderSettings against = settings;
        if (!against_name.empty()) {
            against.ao.method = deepgi::parse_ao_method("--against", against_name);
            against.ao.bias = deepgi::default_ao_bias(against.ao.method);
        }

        if (!baseline_dir.empty() &&
            !std::filesystem::is_regular_file(std::filesystem::path(baseline_dir) / "sao.frag"))
            throw deepgi::InputError(
                fmt::format("--baseline-shaders {} holds no sao.frag", baseline_dir));

        deepgi::HeadlessContext context;
        deepgi::study::ScratchFolder headers;
        const deepgi::ShaderLoader loader = deepgi::study::loader_with_override(headers.path());
        // The run's ao_taps.glsl is not among the baseline's sources.
        std::optional<deepgi::ShaderLoader> baseline_loader;
        if (!baseline_dir.empty())
            baseline_loader = deepgi::bench::with_sources_first(loader, baseline_dir);
        const std::string first_column = baseline_loader ? "baseline, 2 layers" : "1 layer";
        std::string measured;
        fmt::print(
            "| scene | N | tau | {} (ms) | 2 layers (ms) | 2 / {} | blur (ms) | depth pyramid "
            "(ms) |{}\n",
            first_column, baseline_loader ? "baseline" : "1",
            against_name.empty()
                ? ""
                : fmt::format(
                      " {0}, 2 layers (ms) | 2 layers / {0} | normal pair, {0}'s (ms) | 2 layers "
                      "and normal pair / {0} and its | pyramid readers (ms) | {0}: "
                      "depth pyramid, pyramid readers (ms) |",
                      against_name));
        fmt::print("|---|--:|--:|--:|--:|--:|--:|--:|{}\n",
                   against_name.empty() ? "" : "--:|--:|--:|--:|--:|--:|");
        for (const auto& scene_name : options.scenes) {
            const deepgi::Scene scene = deepgi::load_scene(scene_name);
            for (int n : tap_counts) {
                const int tau = spiral::search(n).tau;
                spiral::codegen::write_file_atomically(
                    headers.path() / "ao_taps.glsl",
                    spiral::codegen::make_gather_header("ao", n, tau, {"sao_bench"}));
                deepgi::Renderer one(scene, baseline_loader ? settings : one_layer,
                                     baseline_loader ? *baseline_loader : loader);
                deepgi::Renderer two(scene, settings, loader);
                std::optional<deepgi::Renderer> other;
                if (!against_name.empty()) other.emplace(scene, against, loader);
                std::vector<deepgi::bench::Configuration> timed = {{&one, scene.default_camera},
                                                                   {&two, scene.default_camera}};
                if (other) timed.push_back({&*other, scene.default_camera});
                const auto medians = deepgi::bench::time_alternated(timed, options);
                const double one_ms = medians[0].at("sao");
                const double two_ms = medians[1].at("sao");
                std::string extra;
                if (other) {
                    // What else reads the pyramid, summed: its format may cost them.
                    auto readers = [](const deepgi::bench::PassMedians& passes) {
                        double sum = 0.0;
                        for (const char* pass : {"ao_temporal", "radiosity", "blur"})
                            sum += passes.count(pass) ? passes.at(pass) : 0.0;
                        return sum;
                    };
                    const double other_ms = medians[2].at("sao");
                    auto pair = [](const deepgi::bench::PassMedians& passes) {
                        return passes.count("normal_pair") ? passes.at("normal_pair") : 0.0;
                    };
                    const double pair_ms = pair(medians[1]);
                    const double other_pair_ms = pair(medians[2]);
                    extra = fmt::format(
                        " {:.2f} | {:.2f} | {:.2f}, {:.2f} | {:.2f} | {:.2f} | {:.2f}, {:.2f} |",
                        other_ms, two_ms / other_ms, pair_ms, other_pair_ms,
                        (two_ms + pair_ms) / (other_ms + other_pair_ms), readers(medians[1]),
                        medians[2].at("depth_pyramid"), readers(medians[2]));
                }
                fmt::print("| {} | {} | {} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} |{}\n",
                           scene_name, n, tau, one_ms, two_ms, two_ms / one_ms,
                           medians[1].at("blur"), medians[1].at("depth_pyramid"), extra);
                std::fflush(stdout);
                if (measured.empty()) measured = deepgi::bench::measured_on(two, options);
            }
        }
        fmt::print("\n{}, method {}", measured, method_name);
        if (deepgi::ao_method_marches_slices(settings.ao.method))
            fmt::print(", {} slices x {} steps", slices, steps);
        fmt::print("\n");
        return 0;
    });
}
