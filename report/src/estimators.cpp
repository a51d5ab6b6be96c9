// The report's estimator options (slice costs, flicker frames) and the
// frame-to-frame change of every estimator on one scene.
#include "estimators.hpp"

#include "deepgi/errors.hpp"

#include <fmt/format.h>

#include <chrono>
#include <charconv>
#include <optional>

namespace deepgi::report {

namespace {

// A whole decimal number, or nullopt.
std::optional<int> whole(std::string_view text) {
    int value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size())
        return std::nullopt;
    return value;
}

}  // namespace

SliceCost parse_slice_cost(std::string_view option, std::string_view text) {
    const std::size_t x = text.find('x');
    const auto slices = x == std::string_view::npos ? std::nullopt : whole(text.substr(0, x));
    const auto steps = x == std::string_view::npos ? std::nullopt : whole(text.substr(x + 1));
    if (!slices || !steps)
        throw InputError(
            fmt::format("{} '{}' is not SLICESxSTEPS (e.g. 2x8)", option, std::string(text)));
    if (*slices < 1 || *slices > limits::max_ao_slices || *steps < 1 ||
        *steps > limits::max_ao_steps)
        throw InputError(fmt::format("{} '{}' is out of range (slices 1 to {}, steps 1 to {})",
                                     option, std::string(text), limits::max_ao_slices,
                                     limits::max_ao_steps));
    return {*slices, *steps};
}

void validate(const EstimatorOptions& options) {
    if (options.slice_costs.empty())
        throw InputError("--slice-costs needs at least one SLICESxSTEPS cost");
    for (std::size_t i = 0; i < options.slice_costs.size(); ++i) {
        const SliceCost& cost = options.slice_costs[i];
        if (cost.slices < 1 || cost.slices > limits::max_ao_slices || cost.steps < 1 ||
            cost.steps > limits::max_ao_steps)
            throw InputError(
                fmt::format("--slice-costs {}x{} is out of range (slices 1 to {}, "
                            "steps 1 to {})",
                            cost.slices, cost.steps, limits::max_ao_slices, limits::max_ao_steps));
        for (std::size_t j = 0; j < i; ++j) {
            if (options.slice_costs[j] == cost)
                throw InputError(
                    fmt::format("--slice-costs names {}x{} twice", cost.slices, cost.steps));
        }
    }
    // Two frames at least in the measured half: one change.
    if (options.flicker_frames != 0 && (options.flicker_frames < 4 || options.flicker_frames > 256))
        throw InputError(fmt::format("--flicker-frames {} is out of range (0, or 4 to 256)",
                                     options.flicker_frames));
}

SliceCost image_slice_cost(const EstimatorOptions& options) {
    const AoSettings defaults;
    const SliceCost shipped{defaults.slices, defaults.steps};
    for (const SliceCost& cost : options.slice_costs) {
        if (cost == shipped) return cost;
    }
    return options.slice_costs.empty() ? shipped : options.slice_costs.front();
}

std::vector<FlickerRow> measure_scene_flicker(const SceneSetup& setup,
                                              std::span<const AoMethod> methods,
                                              const EstimatorOptions& options) {
    std::vector<FlickerRow> rows;
    if (options.flicker_frames == 0) return rows;
    const SliceCost cost = image_slice_cost(options);
    auto measure = [&](AoMethod method, const std::string& role, const std::string& pattern,
                       int taps) {
        setup.write_headers(pattern, taps);
        RenderSettings settings = setup.settings;
        settings.ao.method = method;
        settings.ao.bias = default_ao_bias(method);
        settings.ao.layers = setup.image_layers;
        settings.radiosity.layers = setup.image_layers;
        const bool slices = ao_method_marches_slices(method);
        if (slices) {
            settings.ao.slices = cost.slices;
            settings.ao.steps = cost.steps;
        }
        Renderer renderer(setup.scene, settings, setup.loader);
        rows.push_back(
            FlickerRow{.scene = setup.scene_name,
                       .ao_method = std::string(to_string(method)),
                       .role = role,
                       .pattern = pattern,
                       .taps = taps,
                       .slices = slices ? cost.slices : 0,
                       .steps = slices ? cost.steps : 0,
                       .layers = setup.image_layers,
                       .frames = options.flicker_frames,
                       .measure = measure_flicker(renderer, setup.scene, options.flicker_frames)});
    };
    for (AoMethod method : methods)
        measure(method, "estimator", setup.image_pattern, setup.image_taps);
    measure(AoMethod::solid_angle, "floor", "optimal", setup.converged_taps);
    return rows;
}

void measure_flicker_rows(const SceneSetup& setup, const ReportOptions& options,
                          std::vector<FlickerRow>& rows,
                          const std::function<void(const std::string&)>& log) {
    if (options.estimators.flicker_frames == 0) return;
    const auto start = std::chrono::steady_clock::now();
    const auto measured = measure_scene_flicker(setup, options.ao_methods, options.estimators);
    for (const FlickerRow& row : measured) {
        log(fmt::format("{} {} ({}): frame-to-frame change still {:.5f}, path {}", row.scene,
                        row.ao_method, row.role, row.measure.still.mean(),
                        row.measure.has_path ? fmt::format("{:.5f}", row.measure.path.mean())
                                             : std::string("-")));
    }
    log(fmt::format(
        "{}: frame-to-frame change, {:.1f} s", setup.scene_name,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()));
    rows.insert(rows.end(), measured.begin(), measured.end());
}

}  // namespace deepgi::report
