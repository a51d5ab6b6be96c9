#pragma once
// The speed-against-error report (docs/report.md): renders every combination
// of scene, tap pattern, tap count and layer count headless, times the deep
// SAO pass, and measures its visibility against the same estimator at many
// taps and against the ray-traced reference. The production shaders run with
// tap headers written at run time into a scratch folder searched before the
// build's generated headers.
#include "deepgi/hard_cases.hpp"
#include "deepgi/image_io.hpp"
#include "deepgi/report_estimators.hpp"
#include "deepgi/report_reflections.hpp"
#include "deepgi/report_ties.hpp"
#include "deepgi/settings.hpp"

#include <spiral/codegen.hpp>
#include <spiral/float_compare.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace deepgi::report {

// ---------------------------------------------------------------------------
// Tap patterns: every one is a spiral with tap i at radius (i + 1/2) / n and
// angle 2 pi (p / m) (i + 1/2) / n, so all of them go through the optimizer's
// exact discrepancy and the codegen's tap placement.

// optimal (integer search), tau1, golden (tau = n (2 - phi)), m2, m4, m8
// (the fractional optima p / m).
const std::vector<std::string>& pattern_names();
bool is_pattern_name(std::string_view name);

struct Turns {
    std::int64_t p = 1;
    std::int64_t m = 1;
    double value() const { return double(p) / double(m); }
};

// The turns of a pattern at n taps. The golden angle is irrational; it is
// approximated by p / 2^20, which moves no tap by more than 2^-20 of a turn
// (far below float precision of the offsets) and the discrepancy by at most
// 2^-19 (the bound spiralgen's `discrepancy --turns golden` states).
// Throws std::invalid_argument for an unknown name.
Turns pattern_turns(std::string_view name, int n);

// Exact discrepancy D(n, p / m) of a pattern.
double pattern_discrepancy(std::string_view name, int n);

// A gather header with the symbols the shaders read (PREFIX_NUM_TAPS,
// PREFIX_TAP_OFFSETS, PREFIX_TAP_ALPHAS, ...) for any taps.
std::string format_taps_header(std::string_view prefix,
                               const std::vector<spiral::codegen::Tap>& taps, Turns turns,
                               std::string_view what);

// ---------------------------------------------------------------------------
// Error statistics

struct ErrorStats {
    double mae = 0.0;
    double rmse = 0.0;
    double bias = 0.0;  // mean of estimate - truth
    long long pixels = 0;
};

// Over the pixels where mask != 0, of channel-averaged values (the first
// min(channels, 3) channels). Images must have the same size; mask has one
// value per pixel. Throws std::invalid_argument otherwise.
ErrorStats compare_images(const FloatImage& estimate, const FloatImage& truth,
                          const std::vector<std::uint8_t>& mask);

// ---------------------------------------------------------------------------
// Rows

// One value of a row; nullopt where the build cannot measure it (written as
// an empty CSV cell and a JSON null), so the columns stay the same whatever
// the build holds.
struct Value {
    std::string column;
    std::optional<double> value;
};

struct Row {
    std::string scene;
    std::string pattern;
    int taps = 0;
    int layers = 0;
    std::string ao_method;  // to_string(AoMethod)
    // GL_RENDERER of the context that rendered and timed the row, so rows
    // from a GPU and from llvmpipe stay apart when files are merged.
    std::string device;
    std::vector<Value> values;  // same columns in the same order on every row

    std::optional<double> get(std::string_view column) const;
};

// The frame's passes the report times, by the names the frame's timer gives
// them; each becomes the column "<pass>_ms".
const std::vector<std::string>& timed_passes();
// The measured columns, in order; docs/report.md says what each means.
const std::vector<std::string>& value_columns();

// scene,pattern,taps,layers,ao_method,device,<value_columns...>; numbers in shortest
// round-trip form, so reading a file back gives the same doubles. Text fields
// holding a comma or a quote are quoted (RFC 4180): GL_RENDERER often does.
std::string format_csv(const std::vector<Row>& rows);

// One CSV field: as is, or quoted (quotes doubled) when it holds a comma, a
// quote or a line break.
std::string csv_field(std::string_view text);

// ---------------------------------------------------------------------------
// Numerical hard cases (deepgi/hard_cases.hpp): one row per measured quantity
// of one case, with the bound it must keep.

struct StabilityRow {
    std::string ao_method;  // the estimator rendered, as --ao-method names it
    std::string case_name;  // e.g. "scale ref-crease x0.001"
    std::string quantity;   // what value measures
    double value = 0.0;     // NaN when the case produced non-finite output
    std::string test;       // "<=" or ">=": value test tolerance must hold
    double tolerance = 0.0;
    bool pass = false;  // false for a NaN value
};

// Renders every case of `cases` with the build's shaders and tap headers, once
// per AO estimator in `methods`, and measures them as
// tests/runtime/stability_test.cpp checks them. Needs a current GL context;
// `log` (may be empty) gets one line per case.
std::vector<StabilityRow> run_stability_cases(const hard_cases::Parameters& cases,
                                              std::span<const AoMethod> methods,
                                              const std::function<void(const std::string&)>& log);

// ao_method,case,quantity,value,test,tolerance,pass
std::string format_stability_csv(const std::vector<StabilityRow>& rows);

// n,exact_tau,exact_K,float_tau,float_tau_exact_K,denominator,differs,exact_tie:
// one row per n (spiral_float::compare_float_search).
std::string format_float_csv(const std::vector<spiral_float::Choice>& choices);

struct ReportInfo {
    std::string renderer;  // GL_RENDERER
    std::string vendor;    // GL_VENDOR
    bool cpu_clock = true;
    int width = 0, height = 0, guard = 0, rays = 0, converged_taps = 0;
    int warmup = 0, frames = 0;
    // The configuration of the per-scene images, which every AO method runs.
    std::string image_pattern;
    int image_taps = 0;
    int repeats = 1;  // renders of every row, each with its own temporal offset and rotation seed
    // "library": every row at RenderSettings' lengths in metres; "auto": at
    // the command line's, resolved per scene (ReportOptions::scene_lengths).
    // The rows' ao_radius and radiosity_radius columns hold the values.
    std::string lengths = "library";
    // The still run of the radiosity section (ReportOptions::radiosity_frames):
    // its frames (0: not run) and the tap count of the rows that ran it.
    int radiosity_frames = 0;
    int radiosity_taps = 0;
    double seconds = 0.0;
};
// {"info":{...},"rows":[...],"stability":[...],"float_vs_exact":{...}}; the
// last two hold what run_report measured of them (empty when skipped).
std::string format_json(const std::vector<Row>& rows, const ReportInfo& info,
                        const std::vector<StabilityRow>& stability = {},
                        const std::vector<spiral_float::Choice>& float_choices = {});

// ---------------------------------------------------------------------------
// Running it

struct ReportOptions {
    std::vector<std::string> scenes = {"ref-crease", "ref-slab", "ref-board", "ref-bench",
                                       "cornell",    "atrium",   "warehouse", "gallery"};
    std::vector<int> taps = {4, 8, 11, 16, 32, 64};
    std::vector<std::string> patterns = {"optimal", "tau1", "golden", "m2", "m4", "m8"};
    std::vector<int> layers = {1, 2};
    // Deep SAO estimators. The first runs every pattern at every tap count;
    // the others run the image pattern only: at every tap count where the
    // method gathers the spiral's taps, and once (at the image tap count,
    // which the radiosity gather of the row still uses) for the march,
    // whose samples DEEPGI_AO_MARCH_RAYS and _STEPS fix, and for gtao and
    // bitmask at each of estimators.slice_costs.
    std::vector<AoMethod> ao_methods = {AoMethod::solid_angle, AoMethod::published,
                                        AoMethod::march};
    // The slice estimators' costs and the frame-to-frame change (flicker.csv).
    EstimatorOptions estimators;
    int width = 320;
    int height = 180;
    int rays = 512;            // reference rays per pixel; 0: deepgi reference's adaptive budgets
    int converged_taps = 256;  // "converged" screen-space result: optimal pattern at this count
    int warmup = 1;            // untimed frames before the timed ones
    int frames = 5;            // timed frames; the median is reported
    int threads = 0;           // reference threads (0: all)
    std::uint64_t seed = 1;
    // Per-scene images (truth, estimate, signed error) are written for this
    // configuration, or the nearest tap count in the run.
    std::string image_pattern = "optimal";
    int image_taps = 11;
    // Every row is rendered this many times, repeat r with the temporal
    // sequence started at repeat_offset(options, r) (RenderSettings::
    // temporal_offset) and the per-pixel rotation seeded with
    // repeat_rotation_seed(r): another realisation of both the per-frame and
    // the per-pixel rotation. The
    // spread between repeats is the run's own noise, which the summary
    // compares every difference it reports with (docs/report.md).
    int repeats = 2;
    // Every length (radii, thickness, the layers' separation) at `auto`, a
    // fraction of each scene's size, as the command line renders by default
    // (docs/deepgi.md, "Scene scale"); false: the library's metres.
    bool scene_lengths = false;
    // Radiosity after a still camera's running mean of this many frames
    // (the rad_*_still_* columns; 0: not measured), rendered for the rows
    // of the renderer's default radiosity tap count (the --taps value
    // nearest it), the first AO method and the image pattern, every layer
    // count and repeat. The nine frames of the accumulated columns leave
    // much of the gather's noise in its MAE; 64 frames are the convergence
    // target's count (docs/radiosity.md), at which the noise left is a few
    // percent of the irradiance.
    int radiosity_frames = 64;
    // Extras that run only when asked (each adds minutes to a full run):
    // the numerical hard cases (stability.csv), and the exact against the
    // double-precision tau search for n = 1..float_max_n (float_vs_exact.csv;
    // 1024 costs 95 to 130 s on two cores).
    bool stability = false;
    bool float_check = false;
    int float_max_n = 1024;
    // The mirror rows of every scene with mirrors (reflections.csv).
    ReflectionOptions reflections;
    // The tie table (ties.csv), with a tie_error_study run's verdicts.
    TieOptions ties;
    std::filesystem::path output;
    // One line per finished step (for the log); may be empty.
    std::function<void(const std::string&)> log;
    // Called as each step starts (a scene, the stability cases, the float
    // comparison) with the steps done, the steps in all and the step's name;
    // may be empty.
    std::function<void(int done, int total, const std::string& step)> progress;
};

// Throws deepgi::InputError naming the first invalid option.
void validate(const ReportOptions& options);

// The temporal offset of repeat r: whole disjoint stretches of the Sobol
// sequence, each as long as the frames a row renders after its cut
// (max(9, 1 + warmup + frames, radiosity_frames)), so no two repeats share
// a frame's sample.
int repeat_offset(const ReportOptions& options, int repeat);

// The per-pixel rotation seed of repeat r (RenderSettings::rotation_seed): r,
// so repeat 0 renders the shipped field and every other repeat its own.
int repeat_rotation_seed(int repeat);

struct ReportResult {
    std::vector<Row> rows;
    ReportInfo info;
    std::vector<StabilityRow> stability;
    std::vector<spiral_float::Choice> float_choices;  // one per n, in order
    std::vector<FlickerRow> flicker;                  // flicker.csv, when measured
    std::vector<ReflectionRow> reflections;
};

// Renders everything and writes into options.output (created if missing):
// report.csv, report.json, discrepancy.csv (D(n) of every pattern for
// n = 1..64), images/<scene>-truth.pfm and images/<scene>-estimate-<method>.pfm
// per AO method (viewport only, NaN where not compared), stability.csv and float_vs_exact.csv (each
// unless skipped). Needs a current GL context. Every file is
// written atomically.
ReportResult run_report(const ReportOptions& options);

// n,pattern,p,m,discrepancy for n = 1..max_n and every pattern.
std::string format_discrepancy_csv(const std::vector<std::string>& patterns, int max_n);

}  // namespace deepgi::report
