// tie_error_study: is the tie the optimizer picks among several exact minimisers
// of D(n, tau) as good as the others? For every tap count n with more than one
// minimiser, the raw deep SAO of each tied tau is compared with the converged
// estimator (the same estimator at many taps), as the report's "MAE against
// converged, before the blur" column does (docs/results.md), and the mean
// absolute error over the scenes and frames is printed beside the tau the
// tie-break picks (docs/optimizer.md, "Ties").
//
// Every tau of one n sees the same frames: a fresh renderer per pattern and
// its first --frames frames of a still camera, whose patterns are turned by
// the first points of the temporal sequence (shaders/temporal_sequence.h), so
// the rotations are the same for all of them and the comparison is paired.
// Only the raw AV of each frame is compared, never the temporal history.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/report.hpp"
#include "study_headers.hpp"

#include <spiral/fileio.hpp>
#include <spiral/optimizer.hpp>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <cstdio>
#include <map>
#include <regex>

namespace {

// Layer-0 surface pixels of the viewport (guard band left out), as the report
// compares them.
std::vector<std::uint8_t> surface_mask(const deepgi::FloatImage& depth, int guard) {
    std::vector<std::uint8_t> mask(std::size_t(depth.width) * std::size_t(depth.height), 0);
    for (int y = guard; y < depth.height - guard; ++y)
        for (int x = guard; x < depth.width - guard; ++x)
            mask[std::size_t(y) * std::size_t(depth.width) + std::size_t(x)] =
                depth.at(x, y) > 0.0f ? 1 : 0;
    return mask;
}

using Totals = std::map<std::pair<int, int>, double>;  // (n, tau): sum of MAE over scenes

// The table: per n, every tied tau's MAE (mean over the scenes), the tau the
// tie-break picks, the one with the lowest MAE, and their ratio.
void print_table(const std::vector<spiral::SearchResult>& tied, const Totals& total,
                 const std::vector<std::string>& scenes, const std::string& what) {
    const double count = double(scenes.size());
    fmt::print(
        "| n | K | MAE of each tied tau (picked in bold) | picked | lowest MAE | picked / "
        "lowest |\n|--:|--:|:--|--:|--:|--:|\n");
    int picked_lowest = 0;
    double worst_ratio = 1.0;
    for (const spiral::SearchResult& result : tied) {
        std::string cells;
        int best_tau = result.ties.front();
        for (const int tau : result.ties) {
            const double mae = total.at({result.n, tau}) / count;
            if (mae < total.at({result.n, best_tau}) / count) best_tau = tau;
            if (!cells.empty()) cells += ", ";
            cells += tau == result.tau ? fmt::format("**{}: {:.5f}**", tau, mae)
                                       : fmt::format("{}: {:.5f}", tau, mae);
        }
        const double ratio = total.at({result.n, result.tau}) / total.at({result.n, best_tau});
        worst_ratio = std::max(worst_ratio, ratio);
        if (best_tau == result.tau) ++picked_lowest;
        fmt::print("| {} | {} | {} | {} | {} | {:.4f} |\n", result.n, result.scaled, cells,
                   result.tau, best_tau, ratio);
    }
    fmt::print(
        "\n{} tap counts with ties, n = {}..{}; the picked tau has the lowest MAE at {}; "
        "largest picked / lowest {:.4f}. {}\n",
        tied.size(), tied.empty() ? 0 : tied.front().n, tied.empty() ? 0 : tied.back().n,
        picked_lowest, worst_ratio, what);
}

// Reads n,tau,picked,scene,mae rows written by --csv.
Totals read_csv(const std::string& path, std::vector<std::string>& scenes) {
    std::ifstream in(path);
    if (!in) throw deepgi::InputError(fmt::format("--table-from '{}' cannot be read", path));
    Totals total;
    std::string line;
    std::getline(in, line);
    if (line != "n,tau,picked,scene,mae")
        throw deepgi::InputError(
            fmt::format("--table-from '{}' is not a tie_error_study CSV", path));
    while (std::getline(in, line)) {
        if (line == "n,tau,picked,scene,mae") continue;  // files joined with cat
        std::stringstream row(line);
        std::string n, tau, picked, scene, mae;
        if (!std::getline(row, n, ',') || !std::getline(row, tau, ',') ||
            !std::getline(row, picked, ',') || !std::getline(row, scene, ',') ||
            !std::getline(row, mae))
            throw deepgi::InputError(fmt::format("--table-from: bad row '{}'", line));
        total[{std::stoi(n), std::stoi(tau)}] += std::stod(mae);
        if (std::find(scenes.begin(), scenes.end(), scene) == scenes.end()) scenes.push_back(scene);
    }
    return total;
}

}  // namespace

int main(int argc, char** argv) {
    std::string size = "320x180";
    std::vector<std::string> scenes = {"cornell", "atrium", "ref-board"};
    int min_n = 3;
    int max_n = 64;
    int frames = 4;
    int layers = 2;
    int converged_taps = 256;
    std::string csv;
    CLI::App app{
        "tie_error_study: sampling error of every tied tau against the converged deep SAO"};
    app.add_option("--size", size, "WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--scenes", scenes, "Scenes (built-in names or glTF paths)")
        ->delimiter(',')
        ->capture_default_str();
    app.add_option("--min-n", min_n, "Smallest tap count")->capture_default_str();
    app.add_option("--max-n", max_n, "Largest tap count")->capture_default_str();
    app.add_option("--frames", frames, "Frames per pattern (still camera, turned each frame)")
        ->capture_default_str();
    app.add_option("--layers", layers, "Deep G-buffer layers the AO reads (1 or 2)")
        ->capture_default_str();
    app.add_option("--converged-taps", converged_taps, "Taps of the converged estimator")
        ->capture_default_str();
    app.add_option("--csv", csv,
                   "Also write n,tau,picked,scene,mae rows here (rewritten after each scene)");
    std::string table_from;
    app.add_option("--table-from", table_from,
                   "Render nothing: print the table of a --csv file (or several joined) with this "
                   "build's tie-break");
    CLI11_PARSE(app, argc, argv);

    try {
        std::smatch match;
        static const std::regex pattern(R"(^(\d{1,5})x(\d{1,5})$)");
        if (!std::regex_match(size, match, pattern))
            throw deepgi::InputError(fmt::format("--size '{}' is not WIDTHxHEIGHT", size));
        if (min_n < 1 || max_n > 1024 || min_n > max_n)
            throw deepgi::InputError(fmt::format(
                "--min-n {} and --max-n {} must satisfy 1 <= min <= max <= 1024", min_n, max_n));
        if (frames < 1) throw deepgi::InputError("--frames must be at least 1");
        if (layers != 1 && layers != 2) throw deepgi::InputError("--layers must be 1 or 2");
        if (converged_taps < 1 || converged_taps > 1024)
            throw deepgi::InputError("--converged-taps must be in [1, 1024]");
        if (scenes.empty()) throw deepgi::InputError("--scenes is empty");

        deepgi::RenderSettings settings;
        settings.width = std::stoi(match[1].str());
        settings.height = std::stoi(match[2].str());
        settings.shadow_map_size = 256;
        // The spiral gather whose sampling error the report tabulates.
        settings.ao.method = deepgi::AoMethod::solid_angle;
        settings.ao.bias = deepgi::default_ao_bias(settings.ao.method);
        settings.ao.layers = layers;
        settings.radiosity.layers = layers;
        deepgi::validate(settings);
        const int guard = deepgi::frame_layout(settings).guard;

        std::vector<spiral::SearchResult> tied;
        for (int n = min_n; n <= max_n; ++n)
            if (spiral::SearchResult r = spiral::search(n); r.ties.size() > 1)
                tied.push_back(std::move(r));
        if (!table_from.empty()) {
            std::vector<std::string> csv_scenes;
            const Totals total = read_csv(table_from, csv_scenes);
            std::erase_if(tied, [&](const spiral::SearchResult& r) {
                return !total.contains({r.n, r.ties.front()});
            });
            print_table(
                tied, total, csv_scenes,
                fmt::format("From {}; scenes {}.", table_from, fmt::join(csv_scenes, ", ")));
            return 0;
        }

        deepgi::HeadlessContext context;
        deepgi::study::ScratchFolder headers;
        const deepgi::ShaderLoader loader = deepgi::study::loader_with_override(headers.path());
        auto write_pattern = [&](int n, int tau, const std::string& what) {
            spiral::codegen::write_file_atomically(
                headers.path() / "ao_taps.glsl",
                deepgi::study::format_ao_header(spiral::codegen::spiral_taps(n, tau), tau, what));
        };

        // sum of MAE over scenes and frames, per (n, tau)
        Totals total;
        std::string csv_text = "n,tau,picked,scene,mae\n";
        for (const std::string& scene_name : scenes) {
            const deepgi::Scene scene = deepgi::load_scene(scene_name);
            const deepgi::Camera& camera = scene.default_camera;
            // The smallest minimiser, so that the reference does not move with
            // the tie-break it is used to judge.
            const int converged_tau = spiral::search(converged_taps).ties.front();
            write_pattern(converged_taps, converged_tau, "converged");
            deepgi::FloatImage converged;
            std::vector<std::uint8_t> mask;
            {
                deepgi::Renderer renderer(scene, settings, loader);
                renderer.render(camera, deepgi::CameraMotion::cut);
                converged = renderer.read_pass_output("ao-raw");
                mask = surface_mask(renderer.read_pass_output("gbuffer-depth-layer0"), guard);
            }
            for (const spiral::SearchResult& result : tied) {
                for (const int tau : result.ties) {
                    write_pattern(result.n, tau, fmt::format("tie {} of n = {}", tau, result.n));
                    deepgi::Renderer renderer(scene, settings, loader);
                    double sum = 0.0;
                    for (int f = 0; f < frames; ++f) {
                        renderer.render(camera, f == 0 ? deepgi::CameraMotion::cut
                                                       : deepgi::CameraMotion::continuous);
                        sum += deepgi::report::compare_images(renderer.read_pass_output("ao-raw"),
                                                              converged, mask)
                                   .mae;
                    }
                    const double mae = sum / frames;
                    total[{result.n, tau}] += mae;
                    csv_text += fmt::format("{},{},{},{},{:.6f}\n", result.n, tau,
                                            tau == result.tau ? 1 : 0, scene_name, mae);
                }
                std::fprintf(stderr, "\r%s: n = %d", scene_name.c_str(), result.n);
            }
            std::fprintf(stderr, "\n");
            if (!csv.empty()) {
                spiral::fileio::AtomicFile file(csv);
                file.write(csv_text);
                file.commit();
            }
        }

        print_table(
            tied, total, scenes,
            fmt::format(
                "Solid-angle estimator, {} layer(s), raw AV against the same estimator at {} taps "
                "(smallest optimal tau), mean over {} still frame(s) and the scenes {}, {}x{}.",
                layers, converged_taps, frames, fmt::join(scenes, ", "), settings.width,
                settings.height));
        return 0;
    } catch (const deepgi::InputError& error) {
        fmt::print(stderr, "tie_error_study: error: {}\n", error.what());
        return 2;
    } catch (const std::exception& error) {
        fmt::print(stderr, "tie_error_study: error: {}\n", error.what());
        return 1;
    }
}
