// The report's mirror rows (docs/report.md, "Mirror reflections"): one
// reference trace of the reflections per scene with mirrors, then one
// renderer per layer count and step count, taking turns frame by frame so
// that the timings share the machine's state, and each compared with the
// trace over the viewport's mirror pixels.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/reference.hpp"
#include "deepgi/reflection_comparison.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/report.hpp"
#include "deepgi/report_reflections.hpp"

#include <spiral/fileio.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

namespace fs = std::filesystem;

namespace deepgi::report {

namespace {

double median_of(std::vector<double> values) {
    if (values.empty()) return std::nan("");
    std::sort(values.begin(), values.end());
    const std::size_t middle = values.size() / 2;
    return values.size() % 2 == 1 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

bool scene_has_mirror_material(const Scene& scene, float mirror_roughness) {
    return std::any_of(scene.materials.begin(), scene.materials.end(), [&](const Material& m) {
        return m.roughness <= mirror_roughness && m.metallic >= 0.5f;
    });
}

// One configuration's shares and relative errors from the reference
// library's comparison of its images (the key fields stay empty): the
// errors are the filtered radiance's, NaN where the pixels they are taken
// over have no traced radiance.
ReflectionRow reflection_row(const ReflectionComparison& comparison) {
    ReflectionRow row;
    row.mirror_pixels = comparison.mirror_pixels;
    const double n = double(std::max(comparison.mirror_pixels, 1LL));
    row.same_surface = double(comparison.same_surface) / n;
    row.renderer_missed = double(comparison.renderer_missed) / n;
    row.other_surface = double(comparison.wrong_surface) / n;
    row.renderer_only = double(comparison.renderer_only) / n;
    auto relative = [](double sum, double truth) {
        return truth > 0.0 ? sum / truth : std::nan("");
    };
    const RadianceSums& all = comparison.filtered;
    row.rel_mae = relative(all.absolute_error, all.truth);
    row.rel_bias = relative(all.error, all.truth);
    const RadianceSums& same = comparison.same_surface_filtered;
    row.same_surface_rel_mae = relative(same.absolute_error, same.truth);
    row.same_surface_rel_bias = relative(same.error, same.truth);
    row.meets_mirror = double(comparison.meets_mirror) / n;
    const RadianceSums& chain = comparison.meets_mirror_filtered;
    row.meets_mirror_rel_mae = relative(chain.absolute_error, chain.truth);
    row.meets_mirror_rel_bias = relative(chain.error, chain.truth);
    return row;
}

}  // namespace

void validate(const ReflectionOptions& options) {
    if (!options.enabled) return;
    if (options.steps.empty()) throw InputError("--reflection-steps needs at least one step count");
    for (int steps : options.steps) {
        RenderSettings check;
        check.reflection.steps = steps;
        try {
            deepgi::validate(check);
        } catch (const InputError&) {
            throw InputError(fmt::format("--reflection-steps {} is out of range", steps));
        }
    }
    if (options.frames < 1 || options.frames > 1000)
        throw InputError(
            fmt::format("--reflection-frames {} is out of range (1 to 1000)", options.frames));
}

std::vector<ReflectionRow> measure_reflection_rows(
    const std::string& scene_name, const Scene& scene, const RenderSettings& settings,
    const ReflectionOptions& options, const std::vector<int>& layer_counts, int rays,
    std::uint64_t seed, int threads, int warmup,
    const std::function<void(const std::string&)>& log) {
    auto say = [&](const std::string& line) {
        if (log) log(line);
    };
    if (!options.enabled) return {};
    if (!scene_has_mirror_material(scene, settings.mirror_roughness)) {
        say(fmt::format("{}: no mirror material, no mirror rows", scene_name));
        return {};
    }
    // The traced reflections alone: no AO, no irradiance image.
    ReferenceSettings reference;
    reference.render = settings;
    reference.ambient_visibility = false;
    reference.irradiance = false;
    reference.reflections = true;
    reference.radiosity_radius = settings.radiosity.radius;
    if (rays > 0) {
        reference.irradiance_rays.min_rays = rays;
        reference.irradiance_rays.max_rays = rays;
        reference.irradiance_rays.ceiling_max_rays = rays;
        reference.irradiance_rays.target_relative_error = 0.0;
        reference.irradiance_rays.target_absolute_error = 0.0;
    }
    reference.seed = seed;
    reference.threads = threads;
    const auto trace_start = std::chrono::steady_clock::now();
    const RayScene ray_scene(scene);
    const Camera& camera = scene.default_camera;
    const ReferenceImages truth = render_reference(ray_scene, camera, reference);
    say(fmt::format(
        "{}: traced reflections, {:.1f} s", scene_name,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - trace_start).count()));

    // One renderer per configuration, all taking turns frame by frame.
    struct Configuration {
        int layers = 0, steps = 0;
        std::unique_ptr<Renderer> renderer;
        std::vector<double> milliseconds;
    };
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    std::vector<Configuration> configurations;
    for (int layers : layer_counts)
        for (int steps : options.steps) {
            RenderSettings s = settings;
            s.reflection.enabled = true;
            s.reflection.layers = layers;
            s.reflection.steps = steps;
            configurations.push_back(
                {layers, steps, std::make_unique<Renderer>(scene, s, loader), {}});
        }
    for (int frame = 0; frame < options.frames; ++frame)
        for (Configuration& c : configurations) {
            c.renderer->render(camera, frame == 0 ? CameraMotion::cut : CameraMotion::continuous);
            if (frame < std::min(warmup, options.frames - 1)) continue;
            for (const PassTiming& timing : c.renderer->last_timings())
                if (timing.pass == "reflection") c.milliseconds.push_back(timing.milliseconds);
        }

    // Where the traced ray's first surface is itself a mirror.
    std::vector<std::uint8_t> meets_mirror(truth.reflection_hit.pixels.size() / 3, 0);
    for (std::size_t i = 0; i < meets_mirror.size(); ++i) {
        const float triangle = truth.reflection_hit.pixels[3 * i + 1];
        meets_mirror[i] =
            triangle >= 0.0f && ray_scene.mirror(unsigned(triangle), settings.mirror_roughness);
    }
    const int guard = frame_layout(settings).guard;
    std::vector<ReflectionRow> rows;
    for (Configuration& c : configurations) {
        const Renderer& r = *c.renderer;
        const FloatImage depth = r.read_pass_output("gbuffer-depth-layer0");
        const FloatImage hit = r.read_pass_output("reflection-hit");
        const FloatImage filtered = r.read_pass_output("reflection-temporal");
        // Only the filtered radiance is read back: it stands in for this
        // frame's too, which the rows do not report.
        ReflectionRow row = reflection_row(compare_reflection_images(
            {depth, hit, filtered, filtered, truth.depth_layer0, truth.reflection_radiance,
             truth.reflection_hit, truth.surface_layers, &meets_mirror},
            guard));
        if (row.mirror_pixels == 0) {
            say(fmt::format("{}: no mirror pixels in view, no mirror rows", scene_name));
            return {};
        }
        if (c.milliseconds.empty())
            throw std::runtime_error("the frame timed no pass named 'reflection'");
        row.scene = scene_name;
        row.layers = c.layers;
        row.steps = c.steps;
        row.frames = options.frames;
        row.device = query_context_info().renderer;
        row.reflection_ms = median_of(c.milliseconds);
        say(
            fmt::format("{} mirrors layers={} steps={}: same surface {:.3f}, missed {:.3f}, "
                        "rel. MAE {:.3f}, bias {:+.3f}, reflection {:.2f} ms",
                        scene_name, c.layers, c.steps, row.same_surface, row.renderer_missed,
                        row.rel_mae, row.rel_bias, row.reflection_ms));
        rows.push_back(std::move(row));
    }
    return rows;
}

std::string format_reflection_csv(const std::vector<ReflectionRow>& rows) {
    std::string text =
        "scene,layers,steps,frames,device,mirror_pixels,same_surface,renderer_missed,"
        "other_surface,renderer_only,rel_mae,rel_bias,same_surface_rel_mae,"
        "same_surface_rel_bias,meets_mirror,meets_mirror_rel_mae,meets_mirror_rel_bias,"
        "reflection_ms\n";
    auto number = [](double value) {
        return std::isfinite(value) ? fmt::format("{}", value) : std::string();
    };
    for (const ReflectionRow& row : rows)
        text += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
                            csv_field(row.scene), row.layers, row.steps, row.frames,
                            csv_field(row.device), row.mirror_pixels, number(row.same_surface),
                            number(row.renderer_missed), number(row.other_surface),
                            number(row.renderer_only), number(row.rel_mae), number(row.rel_bias),
                            number(row.same_surface_rel_mae), number(row.same_surface_rel_bias),
                            number(row.meets_mirror), number(row.meets_mirror_rel_mae),
                            number(row.meets_mirror_rel_bias), number(row.reflection_ms));
    return text;
}

void write_reflection_table(const fs::path& directory, bool enabled,
                            const std::vector<ReflectionRow>& rows) {
    const fs::path path = directory / "reflections.csv";
    if (!enabled) {
        fs::remove(path);
        return;
    }
    spiral::fileio::AtomicFile file(path);
    file.write(format_reflection_csv(rows));
    file.commit();
}

}  // namespace deepgi::report
