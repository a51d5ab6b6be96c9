// One scene's rows of the report: traces the scene's truth once, renders
// every configuration of every AO method (pattern, tap count, layer count,
// slice cost, repeat) and turns each into a row (value_columns(), format.cpp),
// with the comparisons of compare.cpp. measure.cpp runs it for every scene.
#include "scene_rows.hpp"

#include "compare.hpp"
#include "deepgi/reference.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/report.hpp"
#include "deepgi/settings.hpp"

#include <spiral/optimizer.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace deepgi::report {

namespace {

// A temporal AO pass, when the build has one, publishes its accumulated
// visibility under this name; the report then fills the ref_temporal_*
// columns after kAccumulatedFrames still frames.
constexpr const char* kTemporalAoOutput = "ao-temporal";
// The temporally filtered layer-0 irradiance (radiosity pass).
constexpr const char* kTemporalIrradianceOutput = "radiosity-irradiance-layer0";

// Static frames after a cut until the accumulated columns are read: the
// temporal filters then hold the running mean of that many frames, each
// with a new rotation (frame.cpp), on the way to what a still camera
// converges to. Nine, as when the rotation ran through a cycle of eight.
constexpr int kAccumulatedFrames = 9;

double median(std::vector<double> values) {
    if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(values.begin(), values.end());
    const std::size_t middle = values.size() / 2;
    return values.size() % 2 == 1 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

std::optional<double> finite(double value) {
    if (std::isfinite(value)) return value;
    return std::nullopt;
}

std::string file_stem(const std::string& scene) {
    std::string stem = fs::path(scene).stem().string();
    for (char& c : stem) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-') c = '-';
    }
    return stem.empty() ? "scene" : stem;
}

// What one rendered frame gives the report.
struct Frame {
    FloatImage depth;  // rasterised layer-0 depth
    FloatImage ao_raw;
    FloatImage ao_blurred;
    FloatImage radiosity_raw;
    FloatImage radiosity_blurred;
};

Frame read_frame(const Renderer& renderer) {
    return {renderer.read_pass_output("gbuffer-depth-layer0"), renderer.read_pass_output("ao-raw"),
            clamped_visibility(renderer.read_pass_output("ao-blurred")),
            renderer.read_pass_output("radiosity-raw-layer0"),
            renderer.read_pass_output("radiosity-blurred")};
}

bool has_output(const Renderer& renderer, const std::string& name) {
    const auto names = renderer.pass_output_names();
    return std::find(names.begin(), names.end(), name) != names.end();
}

// The reference's settings for the report's truth. A fixed ray count per
// pixel, or with --rays 0 the budgets of `deepgi reference` (rays until the
// standard error is below their targets), so that the truth's own noise
// stays out of the error.
ReferenceSettings reference_settings(const ReportOptions& options, const RenderSettings& settings) {
    ReferenceSettings reference;
    reference.render = settings;
    if (options.rays > 0) {
        reference.rays.min_rays = options.rays;
        reference.rays.max_rays = options.rays;
        reference.rays.target_error = 0.0;
        reference.irradiance_rays.min_rays = options.rays;
        reference.irradiance_rays.max_rays = options.rays;
        reference.irradiance_rays.ceiling_max_rays = options.rays;
        reference.irradiance_rays.target_relative_error = 0.0;
        reference.irradiance_rays.target_absolute_error = 0.0;
    }
    // One-bounce irradiance within the gather's radius: the rows compare
    // the first frame after a cut, which has no bounce history, so one
    // bounce is what it estimates.
    reference.irradiance = true;
    reference.radiosity_radius = settings.radiosity.radius;
    reference.seed = options.seed;
    reference.threads = options.threads;
    return reference;
}

// What the static frames after a row's cut give: every timed pass's samples,
// and the errors of what the temporal filters accumulated over them.
struct StaticFrames {
    std::map<std::string, std::vector<double>> samples;
    std::optional<ErrorStats> ref_temporal, ref_accum, rad_ref_temporal, rad_ref_accum,
        rad_vis_accum;
    std::optional<double> open_accum, open_core_accum;
    // The radiosity section's still run, on the rows that render it.
    std::optional<double> still_frames;
    std::optional<ErrorStats> rad_ref_still, rad_vis_still;
};

// Continuous static frames after the cut: the timed ones (so history-based
// passes do what they do in an animation), and at least kAccumulatedFrames,
// after which the accumulated errors are read; with still_frames > 0, as many
// as that too, after which the radiosity's still errors are read.
StaticFrames run_static_frames(
    Renderer& renderer, const Camera& camera, const ReportOptions& options, int still_frames,
    const FloatImage& truth_visibility, const std::vector<std::uint8_t>& agreed,
    const std::vector<std::uint8_t>& open_pixels, const std::vector<std::uint8_t>& blur_open_region,
    const std::function<std::optional<ErrorStats>(const FloatImage&)>& against_irradiance,
    const std::function<std::optional<ErrorStats>(const FloatImage&)>& against_visible) {
    StaticFrames after;
    const int timed_end = options.warmup + options.frames;
    // Frame i of the loop is the (i + 2)-th since the cut.
    const int last = std::max({timed_end, kAccumulatedFrames - 1, still_frames - 1});
    auto read_still = [&] {
        const FloatImage irradiance = renderer.read_pass_output("radiosity-blurred");
        after.still_frames = double(still_frames);
        after.rad_ref_still = against_irradiance(irradiance);
        after.rad_vis_still = against_visible(irradiance);
    };
    if (still_frames == 1) read_still();  // the cut's frame alone
    for (int i = 0; i < last; ++i) {
        renderer.render(camera);
        if (i >= options.warmup && i < timed_end) {
            for (const auto& timing : renderer.last_timings())
                after.samples[timing.pass].push_back(timing.milliseconds);
        }
        if (still_frames > 1 && i + 2 == still_frames) read_still();
        if (i + 2 != kAccumulatedFrames) continue;  // the cut was frame 1
        if (has_output(renderer, kTemporalAoOutput)) {
            after.ref_temporal = compare_images(renderer.read_pass_output(kTemporalAoOutput),
                                                truth_visibility, agreed);
        }
        const FloatImage accumulated = clamped_visibility(renderer.read_pass_output("ao-blurred"));
        after.ref_accum = compare_images(accumulated, truth_visibility, agreed);
        after.open_accum = double(count_open(accumulated, agreed, open_pixels).below);
        after.open_core_accum = double(count_open(accumulated, agreed, blur_open_region).below);
        if (has_output(renderer, kTemporalIrradianceOutput)) {
            after.rad_ref_temporal =
                against_irradiance(renderer.read_pass_output(kTemporalIrradianceOutput));
        }
        const FloatImage irradiance = renderer.read_pass_output("radiosity-blurred");
        after.rad_ref_accum = against_irradiance(irradiance);
        after.rad_vis_accum = against_visible(irradiance);
    }
    return after;
}

// Everything one row's columns are made of.
struct Measured {
    double discrepancy = 0.0;
    double turns = 0.0;
    int temporal_offset = 0;              // the repeat's start in the temporal sequence
    int rotation_seed = 0;                // the repeat's per-pixel rotation field
    std::optional<SliceCost> slice_cost;  // gtao and bitmask
    bool gathers_taps = true;             // false: no converged AO to compare with
    ErrorStats conv_raw, conv_blur, ref_raw, ref_blur, rad_raw, rad_blur;
    std::optional<ErrorStats> rad_ref_raw, rad_ref_blur;
    std::optional<ErrorStats> rad_vis_blur;  // against what the row's layers hold
    std::optional<double> rad_unheld_share;  // of the truth's mean, held by no layer
    OpenCount open_raw;                      // the raw AO over every open pixel
    long long open_blur_below = 0;
    long long open_core_raw_below = 0;
    long long open_core_blur_below = 0;
    double ao_radius = 0.0, radiosity_radius = 0.0;  // the row's lengths (scene units)
    StaticFrames after;
};

// The row's values in value_columns() order (format.cpp); `row` has its key
// fields set. Empty cells where the build or the reference cannot measure.
Row make_row(Row row, const Measured& m) {
    const StaticFrames& after = m.after;
    auto add = [&](const std::string& column, std::optional<double> value) {
        row.values.push_back({column, value ? finite(*value) : std::nullopt});
    };
    auto field = [](const std::optional<ErrorStats>& s,
                    double ErrorStats::*member) -> std::optional<double> {
        if (!s) return std::nullopt;
        return (*s).*member;
    };
    add("discrepancy", m.discrepancy);
    add("turns", m.turns);
    add("temporal_offset", double(m.temporal_offset));
    add("rotation_seed", double(m.rotation_seed));
    add("ao_slices", m.slice_cost ? std::optional<double>(m.slice_cost->slices) : std::nullopt);
    add("ao_steps", m.slice_cost ? std::optional<double>(m.slice_cost->steps) : std::nullopt);
    for (const auto& pass : timed_passes()) {
        const auto it = after.samples.find(pass);
        if (it == after.samples.end())
            throw std::runtime_error(
                fmt::format("the frame timed no pass named '{}' (column {}_ms)", pass, pass));
        add(pass + "_ms", median(it->second));
    }
    auto if_gathers = [&](double value) -> std::optional<double> {
        if (!m.gathers_taps) return std::nullopt;
        return value;
    };
    add("conv_raw_mae", if_gathers(m.conv_raw.mae));
    add("conv_raw_rmse", if_gathers(m.conv_raw.rmse));
    add("conv_blur_mae", if_gathers(m.conv_blur.mae));
    add("conv_blur_rmse", if_gathers(m.conv_blur.rmse));
    // MAE, RMSE and bias of one comparison.
    auto add_stats = [&](const std::string& prefix, const std::optional<ErrorStats>& stats) {
        add(prefix + "_mae", field(stats, &ErrorStats::mae));
        add(prefix + "_rmse", field(stats, &ErrorStats::rmse));
        add(prefix + "_bias", field(stats, &ErrorStats::bias));
    };
    add_stats("ref_raw", m.ref_raw);
    add_stats("ref_blur", m.ref_blur);
    add_stats("ref_temporal", after.ref_temporal);
    add_stats("ref_accum", after.ref_accum);
    add("ref_pixels", double(m.ref_blur.pixels));
    add("ref_open_pixels", double(m.open_raw.pixels));
    add("ref_open_raw_below", double(m.open_raw.below));
    add("ref_open_blur_below", double(m.open_blur_below));
    add("ref_open_accum_below", after.open_accum);
    add("ref_open_core_raw_below", double(m.open_core_raw_below));
    add("ref_open_core_blur_below", double(m.open_core_blur_below));
    add("ref_open_core_accum_below", after.open_core_accum);
    add("rad_conv_raw_rel_mae", m.rad_raw.mae);
    add("rad_conv_raw_rel_rmse", m.rad_raw.rmse);
    add("rad_conv_blur_rel_mae", m.rad_blur.mae);
    add("rad_conv_blur_rel_rmse", m.rad_blur.rmse);
    add_stats("rad_ref_raw_rel", m.rad_ref_raw);
    add_stats("rad_ref_blur_rel", m.rad_ref_blur);
    add_stats("rad_ref_temporal_rel", after.rad_ref_temporal);
    add_stats("rad_ref_accum_rel", after.rad_ref_accum);
    add_stats("rad_vis_blur_rel", m.rad_vis_blur);
    add_stats("rad_vis_accum_rel", after.rad_vis_accum);
    add("rad_still_frames", after.still_frames);
    add_stats("rad_ref_still_rel", after.rad_ref_still);
    add_stats("rad_vis_still_rel", after.rad_vis_still);
    add("rad_unheld_share", m.rad_unheld_share);
    add("ao_radius", m.ao_radius);
    add("radiosity_radius", m.radiosity_radius);
    return row;
}

}  // namespace

void measure_scene_rows(const SceneSetup& setup, const ReportOptions& options, ReportResult& result,
                        const std::function<void(const std::string&)>& log) {
    const std::string& scene_name = setup.scene_name;
    const Scene& scene = setup.scene;
    const Camera& camera = scene.default_camera;
    const RenderSettings& settings = setup.settings;
    const ShaderLoader& loader = setup.loader;
    const std::string& image_pattern = setup.image_pattern;
    const int image_taps = setup.image_taps;
    const int image_layers = setup.image_layers;
    const SliceCost image_cost = setup.image_cost;
    const FrameLayout layout = frame_layout(settings);
    const int guard = layout.guard;
    const int internal_width = layout.internal_width;
    const int internal_height = layout.internal_height;

    // The ray-traced truth on the same pixel grid.
    const ReferenceSettings reference = reference_settings(options, settings);
    const auto reference_start = std::chrono::steady_clock::now();
    const RayScene rays(scene);
    const ReferenceImages truth = render_reference(rays, camera, reference);
    const std::optional<FloatImage> truth_irradiance = reference_irradiance(truth);
    std::map<int, std::optional<FloatImage>> truth_visible;
    for (int layers : options.layers) truth_visible[layers] = visible_irradiance(truth, layers);
    // Open pixels: all of them, and those the target counts before and
    // after the blur. They depend on the truth alone.
    const auto open_pixels = open_region(truth.ambient_visibility, 0);
    const auto raw_open_region = open_region(truth.ambient_visibility, 1);
    const auto blur_open_region = open_region(truth.ambient_visibility, DEEPGI_REPORT_BLUR_RADIUS);
    log(fmt::format(
        "{}: reference, {} rays per pixel, {:.1f} s", scene_name,
        options.rays > 0 ? std::to_string(options.rays) : std::string("adaptive"),
        std::chrono::duration<double>(std::chrono::steady_clock::now() - reference_start).count()));

    // The converged screen-space result, one per layer count: AO and
    // radiosity at many taps. Radiosity does not depend on the AO method,
    // so a method that gathers no AO taps (it has no converged AO: it would
    // equal itself) keeps the previous method's frames for its radiosity.
    std::map<int, Frame> converged;
    for (std::size_t method_index = 0; method_index < options.ao_methods.size(); ++method_index) {
        const AoMethod method = options.ao_methods[method_index];
        const std::string method_name(to_string(method));
        RenderSettings method_settings = settings;
        method_settings.ao.method = method;
        method_settings.ao.bias = default_ao_bias(method);
        // The slice estimators run at each of their costs (a curve), the
        // others at one: every cost at every layer count.
        const bool marches_slices = ao_method_marches_slices(method);
        // Each of those is rendered options.repeats times (repeat_offset,
        // repeat_rotation_seed).
        struct CostAndLayers {
            SliceCost cost;
            int layers = 0;
            int repeat = 0;
        };
        std::vector<CostAndLayers> runs;
        for (const SliceCost& cost :
             marches_slices ? options.estimators.slice_costs : std::vector{image_cost}) {
            for (int layers : options.layers) {
                for (int repeat = 0; repeat < options.repeats; ++repeat)
                    runs.push_back({cost, layers, repeat});
            }
        }
        // The AO and the radiosity gather at the row's layer count and cost.
        auto with_layers = [&](int layers, SliceCost cost) {
            RenderSettings s = method_settings;
            s.ao.layers = layers;
            s.radiosity.layers = layers;
            if (marches_slices) {
                s.ao.slices = cost.slices;
                s.ao.steps = cost.steps;
            }
            return s;
        };
        // The first method compares the patterns; the others are curves
        // (or, for the march, one point) beside it (ReportOptions).
        const bool gathers_taps = ao_method_gathers_taps(method);
        const std::vector<std::string> patterns =
            method_index == 0 ? options.patterns : std::vector<std::string>{image_pattern};
        const std::vector<int> tap_counts =
            gathers_taps ? options.taps : std::vector<int>{image_taps};

        if (gathers_taps || converged.empty()) {
            setup.write_headers("optimal", options.converged_taps);
            Renderer renderer(scene, method_settings, loader);
            for (int layers : options.layers) {
                renderer.set_settings(with_layers(layers, image_cost));
                renderer.render(camera, CameraMotion::cut);
                converged[layers] = read_frame(renderer);
            }
        }

        for (const std::string& pattern : patterns) {
            for (int n : tap_counts) {
                setup.write_headers(pattern, n);
                const Turns turns = pattern_turns(pattern, n);
                const double discrepancy = spiral::discrepancy(n, turns.p, turns.m).value();
                Renderer renderer(scene, method_settings, loader);
                result.info.cpu_clock = renderer.timing_uses_cpu_clock();
                for (const CostAndLayers& run : runs) {
                    const SliceCost cost = run.cost;
                    const int layers = run.layers;
                    const int repeat = run.repeat;
                    const int temporal_offset = repeat_offset(options, repeat);
                    RenderSettings repeat_settings = with_layers(layers, cost);
                    repeat_settings.temporal_offset = temporal_offset;
                    // And another field of per-pixel angles: with the temporal
                    // offset alone every repeat shares the hashed field, and a
                    // difference from how a pattern meets that one field would
                    // repeat exactly, unseen by the spread (docs/report.md).
                    repeat_settings.rotation_seed = repeat_rotation_seed(repeat);
                    renderer.set_settings(repeat_settings);
                    // Errors from the first frame after a cut: no history in it.
                    renderer.render(camera, CameraMotion::cut);
                    const Frame frame = read_frame(renderer);
                    const Frame& reference_frame = converged.at(layers);

                    const auto surface =
                        viewport_mask(internal_width, internal_height, guard,
                                      [&](int x, int y) { return frame.depth.at(x, y) > 0.0f; });
                    // Only where raster and ray tracer see the same surface:
                    // silhouette pixels would compare different points.
                    const auto agreed =
                        viewport_mask(internal_width, internal_height, guard, [&](int x, int y) {
                            const float a = frame.depth.at(x, y);
                            const float b = truth.depth_layer0.at(x, y);
                            return a > 0.0f && b > 0.0f && std::abs(a - b) <= 1e-3f * b;
                        });

                    const ErrorStats conv_raw =
                        compare_images(frame.ao_raw, reference_frame.ao_raw, surface);
                    const ErrorStats conv_blur =
                        compare_images(frame.ao_blurred, reference_frame.ao_blurred, surface);
                    const ErrorStats ref_raw =
                        compare_images(frame.ao_raw, truth.ambient_visibility, agreed);
                    const ErrorStats ref_blur =
                        compare_images(frame.ao_blurred, truth.ambient_visibility, agreed);
                    const double radiosity_scale =
                        masked_mean(reference_frame.radiosity_raw, surface);
                    const double radiosity_blur_scale =
                        masked_mean(reference_frame.radiosity_blurred, surface);
                    const ErrorStats rad_raw = relative(
                        compare_images(frame.radiosity_raw, reference_frame.radiosity_raw, surface),
                        radiosity_scale);
                    const ErrorStats rad_blur =
                        relative(compare_images(frame.radiosity_blurred,
                                                reference_frame.radiosity_blurred, surface),
                                 radiosity_blur_scale);
                    // Radiosity against the truth, relative to the truth's mean
                    // over the compared pixels (the same for every stage).
                    const double truth_irradiance_mean =
                        truth_irradiance ? masked_mean(*truth_irradiance, agreed) : 0.0;
                    auto against_irradiance =
                        [&](const FloatImage& estimate) -> std::optional<ErrorStats> {
                        if (!truth_irradiance) return std::nullopt;
                        return relative(compare_images(estimate, *truth_irradiance, agreed),
                                        truth_irradiance_mean);
                    };
                    const std::optional<FloatImage>& visible = truth_visible.at(layers);
                    const double visible_mean = visible ? masked_mean(*visible, agreed) : 0.0;
                    auto against_visible =
                        [&](const FloatImage& estimate) -> std::optional<ErrorStats> {
                        if (!visible) return std::nullopt;
                        return relative(compare_images(estimate, *visible, agreed), visible_mean);
                    };
                    const std::optional<ErrorStats> rad_ref_raw =
                        against_irradiance(frame.radiosity_raw);
                    const std::optional<ErrorStats> rad_ref_blur =
                        against_irradiance(frame.radiosity_blurred);
                    // The radiosity section's rows (ReportOptions::radiosity_frames):
                    // radiosity does not depend on the AO method, so the first
                    // method's rows at the renderer's radiosity tap count.
                    const int still_frames = method_index == 0 && pattern == image_pattern &&
                                                     n == setup.radiosity_taps && cost == image_cost
                                                 ? options.radiosity_frames
                                                 : 0;

                    if (pattern == image_pattern && n == image_taps && layers == image_layers &&
                        repeat == 0 && cost == image_cost) {
                        const std::string stem = file_stem(scene_name);
                        write_pfm(options.output / "images" / (stem + "-truth.pfm"),
                                  crop(truth.ambient_visibility, guard, agreed));
                        write_pfm(options.output / "images" /
                                      (stem + "-estimate-" + method_name + ".pfm"),
                                  crop(frame.ao_blurred, guard, agreed));
                    }

                    Measured measured{
                        .discrepancy = discrepancy,
                        .turns = turns.value(),
                        .temporal_offset = temporal_offset,
                        .rotation_seed = repeat_settings.rotation_seed,
                        .slice_cost =
                            marches_slices ? std::optional<SliceCost>(cost) : std::nullopt,
                        .gathers_taps = gathers_taps,
                        .conv_raw = conv_raw,
                        .conv_blur = conv_blur,
                        .ref_raw = ref_raw,
                        .ref_blur = ref_blur,
                        .rad_raw = rad_raw,
                        .rad_blur = rad_blur,
                        .rad_ref_raw = rad_ref_raw,
                        .rad_ref_blur = rad_ref_blur,
                        .rad_vis_blur = against_visible(frame.radiosity_blurred),
                        .rad_unheld_share =
                            visible && truth_irradiance_mean > 0.0
                                ? std::optional<double>(1.0 - visible_mean / truth_irradiance_mean)
                                : std::nullopt,
                        .open_raw = count_open(frame.ao_raw, agreed, open_pixels),
                        .open_blur_below = count_open(frame.ao_blurred, agreed, open_pixels).below,
                        .open_core_raw_below =
                            count_open(frame.ao_raw, agreed, raw_open_region).below,
                        .open_core_blur_below =
                            count_open(frame.ao_blurred, agreed, blur_open_region).below,
                        .ao_radius = repeat_settings.ao.radius,
                        .radiosity_radius = repeat_settings.radiosity.radius,
                        .after = run_static_frames(renderer, camera, options, still_frames,
                                                   truth.ambient_visibility, agreed, open_pixels,
                                                   blur_open_region, against_irradiance,
                                                   against_visible)};
                    Row row = make_row(Row{.scene = scene_name,
                                           .pattern = pattern,
                                           .taps = n,
                                           .layers = layers,
                                           .ao_method = method_name,
                                           .device = result.info.renderer,
                                           .values = {}},
                                       measured);
                    log(fmt::format(
                        "{} {}{} {} n={} layers={} offset={}: sao {:.2f} ms, MAE vs its "
                        "own converged {}, vs reference {:.4f} raw {:.4f} blurred",
                        scene_name, method_name,
                        marches_slices ? fmt::format(" {}x{}", cost.slices, cost.steps)
                                       : std::string(),
                        pattern, n, layers, temporal_offset, row.get("sao_ms").value_or(0.0),
                        gathers_taps ? fmt::format("{:.4f}", conv_raw.mae) : std::string("-"),
                        ref_raw.mae, ref_blur.mae));
                    result.rows.push_back(std::move(row));
                }
            }
        }
    }
}

}  // namespace deepgi::report
