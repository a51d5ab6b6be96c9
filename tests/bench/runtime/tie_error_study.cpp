// tie_error_study: is the tie the optimizer picks among several exact minimisers
// of D(n, tau) as good as the others? For every tap count n with more than one
// minimiser, the raw deep SAO of each tied tau is compared with the converged
// estimator (the same estimator at many taps), as the report's "MAE against
// converged, before the blur" column does (docs/results.md).
//
// Every tau is rendered --repeats times, repeat r with the temporal sequence
// started at r * frames (the temporal-offset setting) and the per-pixel
// rotation field of seed r (the rotation-seed setting), as the report's
// --repeats does, each a cut and --frames frames of a still camera whose
// patterns the sequence turns. Re-seeding matters: with one field every
// repeat meets the pattern with the same per-pixel rotations, and the
// repeats then miss most of the noise (--keep-rotation-seed reproduces that).
// In one repeat every tau sees the same rotations, so the pick and another
// tie are compared repeat by repeat: the difference of their MAE, its mean
// and its range over the repeats. The report's rule decides (docs/report.md,
// "Noise"): a difference no larger than that spread names no winner
// (docs/optimizer.md, "Ties").
// Only the raw AV of each frame is compared, never the temporal history.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/report.hpp"
#include "deepgi/report_ties.hpp"
#include "study_headers.hpp"

#include <spiral/fileio.hpp>
#include <spiral/optimizer.hpp>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

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

// Each frame-averaged MAE summed over the scenes, and how many scenes, per
// (n, tau, repeat).
struct Cell {
    double sum = 0.0;
    int scenes = 0;
};
using Totals = std::map<std::tuple<int, int, int>, Cell>;

// Whether every tie of `result` has a value in every repeat, from every scene.
bool complete(const spiral::SearchResult& result, const Totals& total, int repeats,
              int scene_count) {
    for (const int tau : result.ties)
        for (int r = 0; r < repeats; ++r)
            if (auto it = total.find({result.n, tau, r});
                it == total.end() || it->second.scenes != scene_count)
                return false;
    return true;
}

std::vector<deepgi::report::TieVerdict> judge(const std::vector<spiral::SearchResult>& tied,
                                              const Totals& total, int repeats) {
    std::vector<deepgi::report::TieVerdict> verdicts;
    for (const spiral::SearchResult& result : tied) {
        deepgi::report::TieErrors errors{.n = result.n, .pick = result.tau, .mae = {}};
        for (const int tau : result.ties)
            for (int r = 0; r < repeats; ++r) {
                const Cell& cell = total.at({result.n, tau, r});
                errors.mae[tau].push_back(cell.sum / double(cell.scenes));
            }
        verdicts.push_back(deepgi::report::judge_ties(errors));
    }
    return verdicts;
}

// Every tied tau's mean MAE over the repeats, the pick in bold.
std::string tie_cells(const spiral::SearchResult& result, const Totals& total, int repeats) {
    std::string cells;
    for (const int tau : result.ties) {
        double sum = 0.0;
        for (int r = 0; r < repeats; ++r) {
            const Cell& cell = total.at({result.n, tau, r});
            sum += cell.sum / double(cell.scenes) / double(repeats);
        }
        if (!cells.empty()) cells += ", ";
        cells += tau == result.tau ? fmt::format("**{}: {:.5f}**", tau, sum)
                                   : fmt::format("{}: {:.5f}", tau, sum);
    }
    return cells;
}

// The table and the counts, split by how many mirror pairs tie. A pair
// (tau, n - tau) is one spiral and its reflection: the rule cannot separate
// them, so the pick's pair is compared with the best other pair, each by the
// mean of its two members (report_ties.hpp).
void print_table(const std::vector<spiral::SearchResult>& tied, const Totals& total,
                 const std::vector<deepgi::report::TieVerdict>& verdicts, int repeats,
                 const std::string& what) {
    fmt::print(
        "| n | K | pairs | MAE of each tied tau, mean of {} repeats (pick in bold) | pick | "
        "best other pair | pick pair MAE | other pair MAE | difference | spread | mirror spread "
        "| verdict |\n"
        "|--:|--:|--:|:--|--:|--:|--:|--:|--:|--:|--:|:--|\n",
        repeats);
    std::map<std::pair<bool, std::string>, std::vector<int>> counts;
    for (std::size_t i = 0; i < verdicts.size(); ++i) {
        const deepgi::report::TieVerdict& v = verdicts[i];
        if (v.other == 0) {
            fmt::print("| {} | {} | {} | {} | {} | - | {:.5f} | - | - | - | {:.5f} | {} |\n", v.n,
                       tied[i].scaled, v.pairs, tie_cells(tied[i], total, repeats), v.pick,
                       v.pick_mae, v.mirror_spread, v.verdict);
        } else {
            fmt::print(
                "| {} | {} | {} | {} | {} | {} | {:.5f} | {:.5f} | {:+.5f} | {:.5f} | {:.5f} | {} "
                "|\n",
                v.n, tied[i].scaled, v.pairs, tie_cells(tied[i], total, repeats), v.pick, v.other,
                v.pick_mae, v.other_mae, v.difference, v.spread, v.mirror_spread, v.verdict);
        }
        counts[{v.pairs > 1, v.verdict}].push_back(v.n);
    }
    fmt::print("\n{} tap counts with ties, {} repeats. {}\n", verdicts.size(), repeats, what);
    for (const bool several : {true, false}) {
        int all = 0;
        for (const auto& [key, ns] : counts)
            if (key.first == several) all += int(ns.size());
        fmt::print("{} ({} n):\n",
                   several ? "Two or more mirror pairs tie" : "One mirror pair ties", all);
        for (const auto& [key, ns] : counts)
            if (key.first == several)
                fmt::print("  {}: {} (n = {})\n", key.second, ns.size(), fmt::join(ns, ", "));
    }
}

void write_atomically(const std::string& path, const std::string& text) {
    spiral::fileio::AtomicFile file(path);
    file.write(text);
    file.commit();
}

constexpr const char* kHeader = "n,tau,picked,scene,repeat,mae";
constexpr const char* kOneRepeatHeader = "n,tau,picked,scene,mae";  // before --repeats

// Reads the rows written by --csv (files joined with cat too); a file without
// the repeat column is one repeat.
Totals read_csv(const std::string& path, std::vector<std::string>& scenes, int& repeats) {
    std::ifstream in(path);
    if (!in) throw deepgi::InputError(fmt::format("--table-from '{}' cannot be read", path));
    Totals total;
    std::string line;
    std::getline(in, line);
    const bool with_repeat = line == kHeader;
    if (!with_repeat && line != kOneRepeatHeader)
        throw deepgi::InputError(
            fmt::format("--table-from '{}' is not a tie_error_study CSV", path));
    repeats = 1;
    while (std::getline(in, line)) {
        if (line == kHeader || line == kOneRepeatHeader) continue;
        std::stringstream row(line);
        std::string n, tau, picked, scene, repeat = "0", mae;
        if (!std::getline(row, n, ',') || !std::getline(row, tau, ',') ||
            !std::getline(row, picked, ',') || !std::getline(row, scene, ',') ||
            (with_repeat && !std::getline(row, repeat, ',')) || !std::getline(row, mae))
            throw deepgi::InputError(fmt::format("--table-from: bad row '{}'", line));
        try {
            Cell& cell = total[{std::stoi(n), std::stoi(tau), std::stoi(repeat)}];
            cell.sum += std::stod(mae);
            ++cell.scenes;
            repeats = std::max(repeats, std::stoi(repeat) + 1);
        } catch (const std::logic_error&) {
            throw deepgi::InputError(fmt::format("--table-from: bad row '{}'", line));
        }
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
    int repeats = 3;
    int layers = 2;
    int converged_taps = 256;
    std::string csv;
    std::string verdicts_csv;
    CLI::App app{
        "tie_error_study: sampling error of every tied tau against the converged deep SAO, "
        "the pick against the best other tie within the run-to-run spread"};
    app.add_option("--size", size, "WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--scenes", scenes, "Scenes (built-in names or glTF paths)")
        ->delimiter(',')
        ->capture_default_str();
    app.add_option("--min-n", min_n, "Smallest tap count")->capture_default_str();
    app.add_option("--max-n", max_n, "Largest tap count")->capture_default_str();
    app.add_option("--frames", frames, "Frames per repeat (still camera, turned each frame)")
        ->capture_default_str();
    app.add_option("--repeats", repeats,
                   "Repeats of every tau, repeat r with the temporal sequence started at "
                   "r * frames (the temporal-offset setting) and rotation seed r")
        ->capture_default_str();
    int first_repeat = 0;
    app.add_option("--first-repeat", first_repeat,
                   "Render repeats first-repeat .. first-repeat + repeats - 1 (their rows are "
                   "those of a longer run, so runs split this way join with cat; their table "
                   "is only printed by --table-from on the joined rows)")
        ->capture_default_str();
    bool keep_rotation_seed = false;
    app.add_flag("--keep-rotation-seed", keep_rotation_seed,
                 "Every repeat keeps rotation seed 0 (the shipped per-pixel field), as the study "
                 "did before it re-seeded");
    app.add_option("--layers", layers, "Deep G-buffer layers the AO reads (1 or 2)")
        ->capture_default_str();
    app.add_option("--converged-taps", converged_taps, "Taps of the converged estimator")
        ->capture_default_str();
    app.add_option("--csv", csv,
                   "Also write n,tau,picked,scene,repeat,mae rows here (rewritten after each n)");
    app.add_option("--verdicts-csv", verdicts_csv,
                   "Also write one row per n (pick, best other, difference, spread, verdict) "
                   "here; deepgi report --ties-from reads it");
    std::string table_from;
    app.add_option("--table-from", table_from,
                   "Render nothing: print the table of a --csv file (or several joined) with this "
                   "build's tie-break");
    std::string rule = "band";
    app.add_option("--pick", rule,
                   "Which tie is judged as the pick: band (the search's tie-break, "
                   "docs/design.md), smallest (the smallest minimiser, the rule before it) or "
                   "largest-pair (the largest minimiser up to n / 2: an observation, no rule)")
        ->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    try {
        const deepgi::ImageSize image = deepgi::parse_size("--size", size);
        if (min_n < 1 || max_n > 1024 || min_n > max_n)
            throw deepgi::InputError(fmt::format(
                "--min-n {} and --max-n {} must satisfy 1 <= min <= max <= 1024", min_n, max_n));
        if (frames < 1 || frames > 1000) throw deepgi::InputError("--frames must be in [1, 1000]");
        if (repeats < 1 || repeats > 16) throw deepgi::InputError("--repeats must be in [1, 16]");
        if (first_repeat < 0 || first_repeat + repeats > 16)
            throw deepgi::InputError("--first-repeat must be in [0, 16 - repeats]");
        if (layers != 1 && layers != 2) throw deepgi::InputError("--layers must be 1 or 2");
        if (converged_taps < 1 || converged_taps > 1024)
            throw deepgi::InputError("--converged-taps must be in [1, 1024]");
        if (scenes.empty()) throw deepgi::InputError("--scenes is empty");
        if (rule != "band" && rule != "smallest" && rule != "largest-pair")
            throw deepgi::InputError(
                fmt::format("--pick '{}' is not band, smallest or largest-pair", rule));

        deepgi::RenderSettings settings;
        settings.width = image.width;
        settings.height = image.height;
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
            if (spiral::SearchResult r = spiral::search(n); r.ties.size() > 1) {
                if (rule == "smallest") r.tau = r.ties.front();
                if (rule == "largest-pair")
                    for (const int tau : r.ties)
                        if (2 * tau <= n) r.tau = tau;
                tied.push_back(std::move(r));
            }
        auto finish = [&](const Totals& total, int scene_count, const std::string& what) {
            std::erase_if(tied, [&](const spiral::SearchResult& r) {
                return !complete(r, total, repeats, scene_count);
            });
            const auto verdicts = judge(tied, total, repeats);
            print_table(tied, total, verdicts, repeats,
                        fmt::format("{} The pick: {}.", what,
                                    rule == "band"       ? "the band-profile tie-break"
                                    : rule == "smallest" ? "the smallest minimiser"
                                                         : "the largest minimiser up to n / 2"));
            if (!verdicts_csv.empty())
                write_atomically(verdicts_csv, deepgi::report::format_verdict_csv(verdicts));
        };
        if (!table_from.empty()) {
            std::vector<std::string> csv_scenes;
            const Totals total = read_csv(table_from, csv_scenes, repeats);
            // The table lists the tied n of --min-n..--max-n: rows outside
            // would be dropped without a word.
            for (const auto& [key, cell] : total)
                if (const int n = std::get<0>(key); n < min_n || n > max_n)
                    throw deepgi::InputError(fmt::format(
                        "--table-from '{}' has rows for n = {}, outside --min-n {} .. --max-n {}",
                        table_from, n, min_n, max_n));
            finish(total, int(csv_scenes.size()),
                   fmt::format("From {}; scenes {}.", table_from, fmt::join(csv_scenes, ", ")));
            return 0;
        }
        if (!csv.empty()) write_atomically(csv, std::string(kHeader) + "\n");  // fails early

        deepgi::HeadlessContext context;
        deepgi::study::ScratchFolder headers;
        const deepgi::ShaderLoader loader = deepgi::study::loader_with_override(headers.path());
        auto write_pattern = [&](int n, int tau, const std::string& what) {
            spiral::codegen::write_file_atomically(
                headers.path() / "ao_taps.glsl",
                deepgi::study::format_ao_header(spiral::codegen::spiral_taps(n, tau), tau, what));
        };

        Totals total;
        std::string csv_text = std::string(kHeader) + "\n";
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
                    for (int r = first_repeat; r < first_repeat + repeats; ++r) {
                        // Every tau sees the same rotations in repeat r, so the
                        // comparison of two tau is paired; the repeats share none.
                        deepgi::RenderSettings repeat_settings = settings;
                        repeat_settings.temporal_offset = r * frames;
                        if (!keep_rotation_seed)
                            repeat_settings.rotation_seed = deepgi::report::repeat_rotation_seed(r);
                        renderer.set_settings(repeat_settings);
                        double sum = 0.0;
                        for (int f = 0; f < frames; ++f) {
                            renderer.render(camera, f == 0 ? deepgi::CameraMotion::cut
                                                           : deepgi::CameraMotion::continuous);
                            sum += deepgi::report::compare_images(
                                       renderer.read_pass_output("ao-raw"), converged, mask)
                                       .mae;
                        }
                        const double mae = sum / frames;
                        Cell& cell = total[{result.n, tau, r}];
                        cell.sum += mae;
                        ++cell.scenes;
                        csv_text += fmt::format("{},{},{},{},{},{:.6f}\n", result.n, tau,
                                                tau == result.tau ? 1 : 0, scene_name, r, mae);
                    }
                }
                if (!csv.empty()) write_atomically(csv, csv_text);  // a stopped run keeps its rows
                std::fprintf(stderr, "\r%s: n = %d", scene_name.c_str(), result.n);
            }
            std::fprintf(stderr, "\n");
        }

        if (first_repeat > 0) {
            // Without repeats 0 .. first_repeat - 1 no n is complete.
            fmt::print(
                "Repeats {} to {} rendered; join their --csv rows with a run's from "
                "repeat 0 and print the table with --table-from.\n",
                first_repeat, first_repeat + repeats - 1);
            return 0;
        }
        finish(total, int(scenes.size()),
               fmt::format("Solid-angle estimator, {} layer(s), raw AV against the same estimator "
                           "at {} taps (smallest optimal tau), mean over {} still frame(s) per "
                           "repeat and the scenes {}, {}x{}; {}.",
                           layers, converged_taps, frames, fmt::join(scenes, ", "), settings.width,
                           settings.height,
                           keep_rotation_seed ? "every repeat with rotation seed 0"
                                              : "repeat r with rotation seed r"));
        return 0;
    } catch (const deepgi::InputError& error) {
        fmt::print(stderr, "tie_error_study: error: {}\n", error.what());
        return 2;
    } catch (const std::exception& error) {
        fmt::print(stderr, "tie_error_study: error: {}\n", error.what());
        return 1;
    }
}
