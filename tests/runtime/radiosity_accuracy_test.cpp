// Deep radiosity against the ray-traced one-bounce irradiance (Embree, the
// reference library) on scenes of lit walls and a floor, where the G-buffer
// sees every surface within the radius: the area estimator must find the
// truth's mean, and the published normalisation must not. The truth is an
// independent Monte Carlo integral of the definition in reference.hpp;
// nothing here is a value recorded from the shader.
#include "deepgi/context.hpp"
#include "deepgi/reference.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "support/targets.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

namespace deepgi::test {
namespace {

constexpr int width = 192, height = 108;

RenderSettings accuracy_settings(RadiosityMethod method) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.shadow_map_size = 1024;
    // One bounce, the reference's quantity; the rest at the defaults.
    settings.radiosity.rho_prop = 0.0f;
    settings.radiosity.method = method;
    return settings;
}

struct Error {
    double truth_mean = 0.0;
    double mae = 0.0;   // mean absolute error over pixels and channels
    double bias = 0.0;  // mean signed error
    long long pixels = 0;
};

// Over the viewport (guard band excluded) where the rasteriser and the ray
// tracer see the same surface, as deepgi_compare_irradiance measures.
Error measure(const FloatImage& estimate, const FloatImage& raster_depth,
              const ReferenceImages& truth, int guard) {
    Error error;
    double sum_abs = 0.0, sum = 0.0, sum_truth = 0.0;
    const FloatImage& traced = truth.depth_layer0;
    for (int y = guard; y < traced.height - guard; ++y) {
        for (int x = guard; x < traced.width - guard; ++x) {
            const float a = raster_depth.at(x, y), b = traced.at(x, y);
            if (!(a > 0.0f && b > 0.0f && std::abs(a - b) <= 1e-3f * b)) continue;
            for (int c = 0; c < 3; ++c) {
                const double e = double(estimate.at(x, y, c)) - truth.irradiance.at(x, y, c);
                sum_abs += std::abs(e);
                sum += e;
                sum_truth += truth.irradiance.at(x, y, c);
            }
            ++error.pixels;
        }
    }
    const double n = 3.0 * double(std::max(error.pixels, 1LL));
    error.truth_mean = sum_truth / n;
    error.mae = sum_abs / n;
    error.bias = sum / n;
    return error;
}

// The targets of the area estimator (docs/radiosity.md, "Accuracy against the
// ray tracer"), relative to the truth's mean: |bias| <= 5%, MAE <= 10%. Both
// are missed today; the regression bounds below are taken from the measured
// values (about 10% above them), not targets. The table goes to
// radiosity-accuracy-targets.md, printed by the ctest entry
// "deepgi_radiosity_accuracy_targets_missed" (support/targets.hpp).
constexpr double bias_target = 0.05, mae_target = 0.10;

spiral::test::TargetTable& targets() {
    // What remains of the bias is surface the G-buffer lacks: taps past the
    // 11-pixel guard band (the 1 m radius spans about 60 pixels here), on
    // ref-board the wall 15 cm behind the board (nearer than the 0.5 m layer
    // separation), and the weight clamp of patches seen at a grazing angle;
    // all make E low. The MAE is mostly the per-pixel noise of 19 taps x 8
    // rotations; the truth's own 2% per pixel averages out over these pixels.
    static spiral::test::TargetTable table(
        "radiosity-accuracy-targets.md",
        {{"area/ref-crease/relative abs(bias)/8 frames", {0.065, "measured 0.057"}},
         {"area/ref-board/relative abs(bias)/8 frames", {0.105, "measured 0.095"}},
         {"area/ref-crease/relative MAE/8 frames", {0.155, "measured 0.14"}},
         {"area/ref-board/relative MAE/8 frames", {0.19, "measured 0.17"}}});
    return table;
}

}  // namespace

TEST_CASE("radiosity accuracy: the area estimator finds the ray-traced irradiance's mean",
          "[radiosity-accuracy]") {
    const auto name = GENERATE(as<std::string>{}, "ref-crease", "ref-board");
    const Scene scene = load_scene(name);
    ReferenceSettings reference;
    reference.render = accuracy_settings(RadiosityMethod::area);
    reference.ambient_visibility = false;
    reference.irradiance = true;
    reference.radiosity_radius = reference.render.radiosity.radius;
    // 2% per pixel is far below the errors checked below, which are means
    // over thousands of pixels.
    reference.irradiance_rays.min_rays = 256;
    reference.irradiance_rays.target_relative_error = 0.02;
    reference.threads = 2;
    const RayScene rays(scene);
    const ReferenceImages truth = render_reference(rays, scene.default_camera, reference);

    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    Error errors[2];
    for (const RadiosityMethod method : {RadiosityMethod::area, RadiosityMethod::published}) {
        const RenderSettings settings = accuracy_settings(method);
        Renderer renderer(scene, settings, loader);
        // Eight still frames: the filtered E is the mean of their 8 gathers.
        for (int frame = 0; frame < 8; ++frame) renderer.render(scene.default_camera);
        errors[method == RadiosityMethod::area ? 0 : 1] = measure(
            renderer.read_pass_output("radiosity-irradiance-layer0"),
            renderer.read_pass_output("gbuffer-depth-layer0"), truth, frame_layout(settings).guard);
    }
    const Error& area = errors[0];
    const Error& published = errors[1];
    INFO(name << ": truth mean " << area.truth_mean << " over " << area.pixels
              << " pixels; area MAE " << area.mae << " bias " << area.bias << "; published MAE "
              << published.mae << " bias " << published.bias);
    REQUIRE(area.pixels > width * height / 4);
    REQUIRE(area.truth_mean > 0.01);
    targets().check_at_most("area/" + name, "relative abs(bias)", "8 frames",
                            std::abs(area.bias) / area.truth_mean, bias_target);
    targets().check_at_most("area/" + name, "relative MAE", "8 frames", area.mae / area.truth_mean,
                            mae_target);
    targets().write();
    // The published normalisation is far off on the same pixels (measured
    // +300%), so the bounds above tell the estimators apart.
    CHECK(published.bias > 0.5 * area.truth_mean);
}

}  // namespace deepgi::test
