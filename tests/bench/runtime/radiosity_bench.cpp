// radiosity_bench: what deep radiosity costs per frame, in one run.
//
// Per scene, two renderers at the same size: the default frame (every pass
// on, two radiosity layers, the AO and the radiosity E through one shared
// bilateral blur), and the same with one radiosity layer (the paper's 1-vs-2
// layer ratio).
// Every pass is timed with a CPU clock around glFinish (--timing gpu for GL
// timer queries on a GPU); medians of --frames frames after --warmup frames
// under the scene's default (static) camera, the two renderers taking turns
// frame by frame. With --visibility-steps N, a third renderer, the default
// frame with the gather's visibility test of N steps, takes turns with them,
// and a second table sets its radiosity pass against the default's. With
// --max-mip-list L1,L2,..., one more renderer per level, the default frame
// with the radiosity taps' MIP level capped there (radiosity-max-mip), takes
// turns with them too, and a table sets its passes against the default's.
// With --baseline-shaders DIR, one more renderer, the default frame built
// from the shader sources in DIR (before a shader change), takes turns with
// them, and a table sets the radiosity, its blur, the prepare pass and the
// frame against it.
#include "bench_harness.hpp"
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>

using Medians = deepgi::bench::PassMedians;

int main(int argc, char** argv) {
    deepgi::bench::Options options;
    options.scenes = deepgi::builtin_scene_names();
    CLI::App app{"radiosity_bench: deep radiosity milliseconds, one layer against two"};
    deepgi::bench::add_options(app, options);
    int visibility_steps = 0;
    app.add_option("--visibility-steps", visibility_steps,
                   "Also time the default frame with the radiosity visibility test of this many "
                   "steps (0: not)")
        ->check(CLI::Range(0, deepgi::limits::max_radiosity_visibility_steps));
    std::vector<int> max_mips;
    app.add_option("--max-mip-list", max_mips,
                   "Also time the default frame with the radiosity taps' MIP level capped at each "
                   "of these levels (radiosity-max-mip)")
        ->delimiter(',')
        ->check(CLI::Range(0, deepgi::limits::max_pyramid_mip_level));
    std::string baseline_dir;
    app.add_option("--baseline-shaders", baseline_dir,
                   "Also time the default frame built from the shader sources in this folder "
                   "(before a shader change), and print its passes against the default's");
    CLI11_PARSE(app, argc, argv);
    return deepgi::bench::run("radiosity_bench", [&] {
        deepgi::bench::finish(options);
        const deepgi::RenderSettings settings = deepgi::bench::settings_for(options);
        deepgi::validate(settings);
        if (!baseline_dir.empty() && !std::filesystem::is_directory(baseline_dir))
            throw deepgi::InputError(
                fmt::format("--baseline-shaders {} is not a folder", baseline_dir));
        deepgi::HeadlessContext context;
        std::string measured;
        std::vector<std::string> order;
        std::vector<std::pair<std::string, Medians>> full_frames;
        std::string visibility_rows;
        std::string cap_rows;
        std::string baseline_rows;
        fmt::print(
            "| scene | radiosity, 1 layer (ms) | radiosity, 2 layers (ms) | 2 / 1 | blur (ms) | "
            "frame, 1 layer (ms) | frame, 2 layers (ms) |\n"
            "|---|---|---|---|---|---|---|\n");
        const deepgi::ShaderLoader loader = deepgi::ShaderLoader::from_build_configuration();
        std::optional<deepgi::ShaderLoader> baseline_loader;
        if (!baseline_dir.empty())
            baseline_loader = deepgi::bench::with_sources_first(loader, baseline_dir);
        for (const auto& name : options.scenes) {
            const deepgi::Scene scene = deepgi::load_scene(name);
            std::vector<std::string> scene_order;
            deepgi::RenderSettings one_layer = settings;
            one_layer.radiosity.layers = 1;
            deepgi::Renderer two_layers(scene, settings, loader);
            deepgi::Renderer one_layers(scene, one_layer, loader);
            deepgi::RenderSettings with_visibility = settings;
            with_visibility.radiosity.visibility_steps = visibility_steps;
            std::optional<deepgi::Renderer> visible;
            if (visibility_steps > 0) visible.emplace(scene, with_visibility, loader);
            std::vector<deepgi::bench::Configuration> timed = {{&two_layers, scene.default_camera},
                                                               {&one_layers, scene.default_camera}};
            if (visible) timed.push_back({&*visible, scene.default_camera});
            std::vector<std::unique_ptr<deepgi::Renderer>> capped;
            for (int level : max_mips) {
                deepgi::RenderSettings cap = settings;
                cap.radiosity.max_mip_level = level;
                capped.push_back(std::make_unique<deepgi::Renderer>(scene, cap, loader));
                timed.push_back({capped.back().get(), scene.default_camera});
            }
            std::optional<deepgi::Renderer> baseline;
            if (baseline_loader) {
                baseline.emplace(scene, settings, *baseline_loader);
                timed.push_back({&*baseline, scene.default_camera});
            }
            const std::vector<Medians> medians = deepgi::bench::time_alternated(timed, options);
            if (baseline) {
                const Medians& now = medians[0];
                const Medians& before = medians.back();
                // The radiosity pass holds the gather and its temporal
                // filter; the blur filters E and the AO together.
                // The prepare pass builds what the gather reads.
                const double now_gi = now.at("radiosity") + now.at("blur");
                const double before_gi = before.at("radiosity") + before.at("blur");
                const double now_all = now_gi + now.at("radiosity_prepare");
                const double before_all = before_gi + before.at("radiosity_prepare");
                baseline_rows += fmt::format(
                    "| {} | {:.1f} | {:.1f} | {:.2f} | {:.2f} "
                    "| {:.1f} | {:.1f} | {:.2f} | {:.2f} "
                    "| {:.1f} | {:.1f} | {:.2f} |\n",
                    name, before.at("radiosity"), now.at("radiosity"),
                    now.at("radiosity") / before.at("radiosity"), now_gi / before_gi,
                    before.at("radiosity_prepare"), now.at("radiosity_prepare"),
                    now.at("radiosity_prepare") / before.at("radiosity_prepare"),
                    now_all / before_all, before.at("total"), now.at("total"),
                    now.at("total") / before.at("total"));
            }
            for (std::size_t k = 0; k < max_mips.size(); ++k) {
                const Medians& base = medians[0];
                const Medians& cap = medians[timed.size() - max_mips.size() + k];
                // The gather is the radiosity pass's first part; the
                // temporal filter and blur read as many texels at any cap.
                const double base_gi = base.at("radiosity") + base.at("blur");
                const double cap_gi = cap.at("radiosity") + cap.at("blur");
                cap_rows += fmt::format(
                    "| {} | {} | {:.1f} | {:.1f} | {:.2f} | {:.2f} | {:.1f} | {:.1f} | {:.2f} |\n",
                    name, max_mips[k], base.at("radiosity"), cap.at("radiosity"),
                    cap.at("radiosity") / base.at("radiosity"), cap_gi / base_gi, base.at("total"),
                    cap.at("total"), cap.at("total") / base.at("total"));
            }
            if (visible) {
                const Medians& off = medians[0];
                const Medians& on = medians[2];
                visibility_rows +=
                    fmt::format("| {} | {:.1f} | {:.1f} | {:.2f} | {:.1f} | {:.1f} | {:.2f} |\n",
                                name, off.at("radiosity"), on.at("radiosity"),
                                on.at("radiosity") / off.at("radiosity"), off.at("total"),
                                on.at("total"), on.at("total") / off.at("total"));
            }
            for (const auto& timing : two_layers.last_timings()) scene_order.push_back(timing.pass);
            if (measured.empty()) measured = deepgi::bench::measured_on(two_layers, options);
            const Medians& two = medians[0];
            const Medians& one = medians[1];
            fmt::print("| {} | {:.1f} | {:.1f} | {:.2f} | {:.1f} | {:.1f} | {:.1f} |\n", name,
                       one.at("radiosity"), two.at("radiosity"),
                       two.at("radiosity") / one.at("radiosity"), two.at("blur"), one.at("total"),
                       two.at("total"));
            std::fflush(stdout);
            // Every scene's passes, so that a pass one scene adds (the
            // gallery's reflections) gets its column: each new pass goes
            // after the pass that precedes it in its own scene.
            for (std::size_t k = 0; k < scene_order.size(); ++k) {
                if (std::find(order.begin(), order.end(), scene_order[k]) != order.end()) continue;
                auto at = order.begin();
                if (k > 0) {
                    const auto previous = std::find(order.begin(), order.end(), scene_order[k - 1]);
                    if (previous != order.end()) at = previous + 1;
                }
                order.insert(at, scene_order[k]);
            }
            full_frames.emplace_back(name, two);
        }

        if (!visibility_rows.empty())
            fmt::print(
                "\nVisibility test of {} steps against none (two layers):\n\n"
                "| scene | radiosity, none (ms) | radiosity, test (ms) | ratio | frame, none (ms) "
                "| "
                "frame, test (ms) | ratio |\n|---|---|---|---|---|---|---|\n{}",
                visibility_steps, visibility_rows);
        if (!cap_rows.empty())
            fmt::print(
                "\nRadiosity taps' MIP level capped against the default (two layers):\n\n"
                "| scene | cap | radiosity, default (ms) | radiosity, cap (ms) | ratio | "
                "radiosity + blur ratio | frame, default (ms) | frame, cap (ms) | ratio |\n"
                "|---|--:|--:|--:|--:|--:|--:|--:|--:|\n{}",
                cap_rows);
        if (!baseline_rows.empty())
            fmt::print(
                "\nThe default frame against the baseline shaders (two layers):\n\n"
                "| scene | radiosity, baseline (ms) | radiosity, now (ms) | ratio | radiosity + "
                "blur ratio | prepare, baseline (ms) | prepare, now (ms) | ratio | prepare + "
                "radiosity + blur ratio | frame, baseline (ms) | frame, now (ms) | ratio |\n"
                "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n{}",
                baseline_rows);
        fmt::print("\n{}\n", measured);
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
    });
}
