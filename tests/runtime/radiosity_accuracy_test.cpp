// Deep radiosity against the ray-traced one-bounce irradiance (Embree, the
// reference library) on scenes of lit walls and a floor, where the G-buffer
// sees every surface within the radius: the area estimator must find the
// truth's mean, and the published normalisation must not. The truth is an
// independent Monte Carlo integral of the definition in reference.hpp;
// nothing here is a value recorded from the shader. Also atrium's banners,
// which a second layer should let tint the floor and the columns before them
// (a target, 2 layers against 1, with the misses in the targets table), and
// which must move the tint the way the ray-traced visible truth moves it (a
// check).
#include "deepgi/context.hpp"
#include "deepgi/reference.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "support/targets.hpp"

#include <fmt/format.h>
#include <glm/glm.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace deepgi::test {
namespace {

constexpr int width = 192, height = 108;

// The targets are about the estimator's accuracy, so its error is read after
// 64 still frames, where the temporal filter has averaged most of the
// per-frame noise away: after 8 frames that noise was most of the MAE
// (ref-crease against the visible truth, before the blur, 0.136 after 8,
// 0.070 after 64), while the bias moved by under 0.003.
constexpr int accuracy_frames = 64;

RenderSettings accuracy_settings(RadiosityMethod method) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    // The default shadow map, so that the direct light the gather reads is
    // the one users get (with a 1024-texel map the PCF's darkened seams made
    // ref-crease's E 0.16% of the truth darker; docs/deepgi.md, "Shadows").
    // One bounce, the reference's quantity; the rest at the defaults.
    settings.radiosity.rho_prop = 0.0f;
    settings.radiosity.method = method;
    return settings;
}

// The same with the scene's lengths as deepgi picks them by default
// (docs/deepgi.md, "Scene scale"): radii and minimum separation derived from
// the scene's bounding radius.
RenderSettings with_scene_lengths(RenderSettings settings, const Scene& scene) {
    settings.radiosity.radius = settings.min_separation = settings.ao.radius = auto_length;
    return resolve_auto_lengths(settings, scene_scale(scene));
}

struct Error {
    double truth_mean = 0.0;
    double mae = 0.0;   // mean absolute error over pixels and channels
    double bias = 0.0;  // mean signed error
    long long pixels = 0;
};

// Over the viewport (guard band excluded) where the rasteriser and the ray
// tracer see the same surface, as deepgi_compare_irradiance measures.
// `light` is the truth compared with: the whole irradiance, or the part
// whose source the layers hold.
Error measure(const FloatImage& estimate, const FloatImage& raster_depth,
              const ReferenceImages& truth, const FloatImage& light, int guard) {
    Error error;
    double sum_abs = 0.0, sum = 0.0, sum_truth = 0.0;
    const FloatImage& traced = truth.depth_layer0;
    for (int y = guard; y < traced.height - guard; ++y) {
        for (int x = guard; x < traced.width - guard; ++x) {
            const float a = raster_depth.at(x, y), b = traced.at(x, y);
            if (!(a > 0.0f && b > 0.0f && std::abs(a - b) <= 1e-3f * b)) continue;
            for (int c = 0; c < 3; ++c) {
                const double e = double(estimate.at(x, y, c)) - light.at(x, y, c);
                sum_abs += std::abs(e);
                sum += e;
                sum_truth += light.at(x, y, c);
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
// are missed on ref-board; the regression bounds below are taken from the measured
// values (about 10% above them), not targets. The table goes to
// radiosity-accuracy-targets.md, printed by the ctest entry
// "deepgi_radiosity_accuracy_targets_missed" (support/targets.hpp).
constexpr double bias_target = 0.05, mae_target = 0.10;

spiral::test::TargetTable& targets() {
    // What remains of the bias is surface the G-buffer lacks: taps past the
    // 11-pixel guard band (the 1 m radius spans about 60 pixels here), on
    // ref-board the wall 15 cm behind the board (nearer than the 0.5 m layer
    // separation), and the weight clamp of patches seen at a grazing angle;
    // all make E low. What MAE remains after 64 frames is mostly that bias
    // and the crease's pixels; the truth's own 2% per pixel averages out
    // over these pixels.
    static spiral::test::TargetTable table(
        "radiosity-accuracy-targets.md",
        // Measured with the direct light stored as RGBA16F (it was
        // R11F_G11F_B10F, which llvmpipe truncates: E 1.5% darker on
        // ref-crease; docs/radiosity.md, "Where the error against the visible
        // truth comes from"). The whole truth's misses are the light no layer
        // holds (taps past the guard band) and the crease's pixels.
        // Measured after 64 still frames (accuracy_frames), blurred. Met
        // there and hard checks: ref-crease's MAE against both truths (0.058,
        // 0.045) and its bias against both (0.042, 0.027), and ref-board's
        // MAE against both (0.086, 0.060) and its bias against the visible
        // truth (0.042). The last two biases were misses (0.055, 0.058) until
        // the disk widened towards the projection of the ball of radius r
        // (docs/radiosity.md, "The screen disk"): half of ref-board's was the
        // surface within the radius in 3D but outside the disk the taps swept.
        {{"area/ref-board/relative abs(bias)/64 frames", {0.078, "measured 0.0709"}},
         // With the scene's own lengths (a 4.5-unit radius, 0.75 of the
         // 6-unit wall; 17 units at 0.6 of the bounding radius, where these
         // were 0.41 and 0.53) much of the whole truth comes from surfaces
         // no layer holds, which no gather over the layers can find
         // (docs/radiosity.md, "Against the light the layers hold"); against
         // the visible truth both targets are met there (hard checks).
         {"area/ref-crease, lengths auto/relative abs(bias)/64 frames", {0.336, "measured 0.306"}},
         {"area/ref-crease, lengths auto/relative MAE/64 frames", {0.338, "measured 0.307"}},
         {"area/ref-board, lengths auto/relative abs(bias)/64 frames", {0.406, "measured 0.369"}},
         {"area/ref-board, lengths auto/relative MAE/64 frames", {0.409, "measured 0.372"}},
         // The blue banner (x = -4, seen obliquely): with two layers the
         // floor before it turns away from blue (tint 1 layer 0.062, 2
         // layers -0.009 at 192x108), and so does the ray-traced visible
         // truth (E0 0.086, E0 + E1 -0.069): what layer 1 holds there
         // lights that floor with colours away from blue. The target asks
         // what the truth does not; the hard check below follows the truth.
         // (Before the prefiltered levels the difference was 0.0695; with a
         // 1024-texel shadow map 0.0828.)
         // The widened disk of docs/radiosity.md, "The screen disk", moved it
         // further the truth's way (0.0712 before).
         {"atrium/banner 0/floor tint, 1 layer - 2 layers/8 frames", {0.106, "measured 0.0961"}},
         // Magenta leaned toward its banner by under 1e-3 with fixed radii;
         // with the radial shift it leans away by as little: a difference
         // at the level of 8 frames' noise. (Red, banner 4, did too with the
         // R2 sequence; with the Sobol sequence it meets the target after 8
         // frames and leans away by 4e-4 after 64: the truth itself moves by
         // 0.001 there, so red's target is at the level of noise too. With
         // the widened disk both lean away after 8 frames, red by 3e-5.)
         {"atrium/banner 3/floor tint, 1 layer - 2 layers/8 frames", {0.005, "measured 0.0020"}},
         {"atrium/banner 4/floor tint, 1 layer - 2 layers/8 frames", {0.005, "measured 0.00003"}},
         // The columns' sides: before the blue and the magenta banners the
         // side the camera sees turns away from the banner with two layers,
         // as the visible truth does (E0 -0.078 to E0 + E1 -0.165 before
         // blue, -0.003 to -0.054 before magenta; the renderer -0.081 to
         // -0.153 and -0.032 to -0.061): what layer 1 adds there is mostly
         // the other banners and the stone, not the strip of banner beside
         // the column. Yellow and red meet the target.
         {"atrium/banner 0/column tint, 1 layer - 2 layers/8 frames", {0.080, "measured 0.0724"}},
         // The widened disk moved magenta's further the truth's way (0.0289
         // before; the truth's change -0.051).
         {"atrium/banner 3/column tint, 1 layer - 2 layers/8 frames", {0.077, "measured 0.0698"}}});
    return table;
}

}  // namespace

TEST_CASE("radiosity accuracy: the area estimator finds the ray-traced irradiance's mean",
          "[radiosity-accuracy]") {
    const auto scene_name = GENERATE(as<std::string>{}, "ref-crease", "ref-board");
    // The library's 1 m lengths, and the lengths deepgi derives from the
    // scene by default (docs/deepgi.md, "Scene scale": a radius of 4.5 scene
    // units on these scenes), where the heavy tail of the area weight is
    // longer (docs/radiosity.md, "The clamp").
    const bool auto_lengths = GENERATE(false, true);
    const std::string name = scene_name + (auto_lengths ? ", lengths auto" : "");
    const Scene scene = load_scene(scene_name);
    const auto settings_for = [&](RadiosityMethod method) {
        const RenderSettings settings = accuracy_settings(method);
        return auto_lengths ? with_scene_lengths(settings, scene) : settings;
    };
    ReferenceSettings reference;
    reference.render = settings_for(RadiosityMethod::area);
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
    // The visible truth: light whose source layer 0 or layer 1 holds
    // (docs/radiosity.md, "Against the light the layers hold"), what two
    // layers can find at best.
    FloatImage visible = truth.irradiance_layer0;
    REQUIRE(visible.pixels.size() == truth.irradiance_layer1.pixels.size());
    for (std::size_t i = 0; i < visible.pixels.size(); ++i)
        visible.pixels[i] += truth.irradiance_layer1.pixels[i];
    Error errors[2];
    Error area_visible;
    for (const RadiosityMethod method : {RadiosityMethod::area, RadiosityMethod::published}) {
        const RenderSettings settings = settings_for(method);
        Renderer renderer(scene, settings, loader);
        // Still frames: the filtered E is the mean of their gathers. What is
        // measured is the blurred E, which compose reads (and the split
        // tables of docs/radiosity-studies.md measure): before the blur, the
        // per-pixel noise of 64 frames was most of the MAE with the scene's
        // lengths (0.120 and 0.116 against the visible truth, 0.035 and
        // 0.043 blurred), whose taps then swept a 17-unit disk.
        for (int frame = 0; frame < accuracy_frames; ++frame) renderer.render(scene.default_camera);
        const FloatImage e = renderer.read_pass_output("radiosity-blurred");
        const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
        const int guard = frame_layout(settings).guard;
        errors[method == RadiosityMethod::area ? 0 : 1] =
            measure(e, depth, truth, truth.irradiance, guard);
        if (method == RadiosityMethod::area)
            area_visible = measure(e, depth, truth, visible, guard);
    }
    const Error& area = errors[0];
    const Error& published = errors[1];
    INFO(name << ": truth mean " << area.truth_mean << " over " << area.pixels
              << " pixels; area MAE " << area.mae << " bias " << area.bias << "; published MAE "
              << published.mae << " bias " << published.bias);
    REQUIRE(area.pixels > width * height / 4);
    REQUIRE(area.truth_mean > 0.01);
    targets().check_at_most("area/" + name, "relative abs(bias)", "64 frames",
                            std::abs(area.bias) / area.truth_mean, bias_target);
    targets().check_at_most("area/" + name, "relative MAE", "64 frames", area.mae / area.truth_mean,
                            mae_target);
    INFO("against the visible truth: mean " << area_visible.truth_mean << ", MAE "
                                            << area_visible.mae << ", bias " << area_visible.bias);
    REQUIRE(area_visible.truth_mean > 0.01);
    targets().check_at_most("area/" + name, "relative abs(bias), visible truth", "64 frames",
                            std::abs(area_visible.bias) / area_visible.truth_mean, bias_target);
    targets().check_at_most("area/" + name, "relative MAE, visible truth", "64 frames",
                            area_visible.mae / area_visible.truth_mean, mae_target);
    targets().write();
    // The published normalisation is far off on the same pixels (measured
    // +300% at 1 m), so the bounds above tell the estimators apart. With the
    // scene's lengths half the whole truth lies beyond the layers, which
    // hides its excess there (+25%): the check is the 1 m case's.
    if (!auto_lengths) CHECK(published.bias > 0.5 * area.truth_mean);
}

namespace {

// The banner colours of atrium's far side (side 0 of make_atrium in
// scene_builtin.cpp, copied): banner i hangs at x = 2 (i - 2), z = -7.3,
// 1.1 m wide, directly behind a column at z = -6 that hides most of it
// from the default camera; only layer 1 holds what the column hides.
constexpr glm::vec3 far_banners[] = {{0.05f, 0.12f, 0.80f},
                                     {0.85f, 0.68f, 0.04f},
                                     {0.05f, 0.70f, 0.15f},
                                     {0.72f, 0.05f, 0.62f},
                                     {0.80f, 0.04f, 0.04f}};

// Where the tint is read: the floor in front of banner i (within its width,
// from the banner to 2.3 m before it), or the side faces of the column in
// front of it (half as wide as the banner, so a side looks past the column
// at the strip of banner beside it), over the banner's height. The camera
// at x = 0 sees the +x side of the columns left of it and the -x side of
// those right of it; it sees neither side of the middle column.
enum class BannerRegion { floor, column_sides };

// Which banner's region pixel (x, y) of layer 0 lies on, or -1. `point`
// receives the world position.
int banner_region(const FloatImage& depth, int x, int y, const Camera& camera,
                  const RenderSettings& settings, BannerRegion region, glm::vec3& point) {
    const float d = depth.at(x, y);
    if (d <= 0.0f) return -1;
    const glm::mat4 camera_to_world = glm::inverse(camera_view_matrix(camera));
    const glm::vec3 ray = camera_ray_direction(camera, settings, float(x) + 0.5f, float(y) + 0.5f);
    point = glm::vec3(camera_to_world * glm::vec4(ray * d, 1.0f));
    const int i = int(std::lround(point.x / 2.0f)) + 2;
    if (i < 0 || i > 4) return -1;
    const float across = std::abs(point.x - 2.0f * float(i - 2));
    if (region == BannerRegion::floor) {
        if (point.y > 0.02f || point.z < -7.25f || point.z > -4.95f || across > 0.55f) return -1;
        return i;
    }
    // A side face of the column (0.6 m square, z from -6.3 to -5.7), away
    // from its edges, where the banner hangs (1.5 m to 4.6 m up; the column
    // is 4 m tall).
    if (std::abs(across - 0.3f) > 0.01f || point.z < -6.28f || point.z > -5.72f || point.y < 1.5f ||
        point.y > 3.98f)
        return -1;
    return i;
}

// E's chromaticity toward banner i's: (e - 1/3) . (b - 1/3) / |b - 1/3|,
// e = E / sum E, b the banner's; 0 for black.
double tint_toward(glm::dvec3 irradiance, int i) {
    const double total = irradiance.x + irradiance.y + irradiance.z;
    if (!(total > 0.0)) return 0.0;
    const glm::dvec3 b =
        glm::dvec3(far_banners[i]) / double(far_banners[i].x + far_banners[i].y + far_banners[i].z);
    return glm::dot(irradiance / total - 1.0 / 3.0, glm::normalize(b - 1.0 / 3.0));
}

// Mean over banner i's region of E's tint toward the banner.
std::array<double, 5> banner_tint(const FloatImage& e, const FloatImage& depth,
                                  const Camera& camera, const RenderSettings& settings,
                                  BannerRegion region, std::array<int, 5>& counts) {
    std::array<double, 5> sums{};
    counts = {};
    for (int y = 0; y < depth.height; ++y) {
        for (int x = 0; x < depth.width; ++x) {
            glm::vec3 point;
            const int i = banner_region(depth, x, y, camera, settings, region, point);
            if (i < 0) continue;
            const glm::dvec3 irradiance(e.at(x, y, 0), e.at(x, y, 1), e.at(x, y, 2));
            if (!(irradiance.x + irradiance.y + irradiance.z > 0.0)) continue;
            sums[std::size_t(i)] += tint_toward(irradiance, i);
            ++counts[std::size_t(i)];
        }
    }
    for (int i = 0; i < 5; ++i) sums[std::size_t(i)] /= std::max(counts[std::size_t(i)], 1);
    return sums;
}

// The same mean for the ray-traced visible truth: E0 (what one layer can
// find) and E0 + E1 (two layers), irradiance_at() on every pixel of the
// region (reference.hpp), 1024 directions each.
struct VisibleTint {
    std::array<double, 5> one_layer{}, two_layers{};
};
VisibleTint banner_visible_tint(const Scene& scene, const FloatImage& depth,
                                const RenderSettings& settings, BannerRegion region) {
    const RayScene rays(scene);
    const LayerClassifier classify = layer_classifier(rays, scene.default_camera, settings);
    const glm::vec3 eye = glm::vec3(glm::inverse(camera_view_matrix(scene.default_camera))[3]);
    IrradianceRayBudget budget;
    budget.min_rays = budget.max_rays = budget.ceiling_max_rays = 1024;
    VisibleTint tint;
    std::array<int, 5> counts{};
    for (int y = 0; y < depth.height; ++y) {
        for (int x = 0; x < depth.width; ++x) {
            glm::vec3 point;
            const int i = banner_region(depth, x, y, scene.default_camera, settings, region, point);
            if (i < 0) continue;
            const glm::vec3 direction = point - eye;
            const RayScene::Hit hit = rays.intersect_front(eye, glm::normalize(direction), 0.0f,
                                                           1.001f * glm::length(direction));
            if (!hit.hit) continue;
            const glm::vec3 x_point = eye + glm::normalize(direction) * hit.distance;
            const IrradianceSample sample =
                irradiance_at(rays, x_point, hit.normal, settings.radiosity.radius, budget,
                              std::uint64_t(y) * 4096u + std::uint64_t(x), 1, classify);
            const auto k = std::size_t(i);
            tint.one_layer[k] += tint_toward(sample.by_layer[0], i);
            tint.two_layers[k] += tint_toward(sample.by_layer[0] + sample.by_layer[1], i);
            ++counts[k];
        }
    }
    for (std::size_t k = 0; k < 5; ++k) {
        tint.one_layer[k] /= std::max(counts[k], 1);
        tint.two_layers[k] /= std::max(counts[k], 1);
    }
    return tint;
}

}  // namespace

// The banners of atrium hang behind the columns, so layer 0 holds only
// their edges; a second layer should add the light of the hidden part to
// the floor in front of them, and to the sides of the columns, which turn
// toward the banner's colour. The target: for every banner, each region's
// tint toward it is higher with two layers than with one. A banner that
// misses it is listed in the targets table (a regression bound at the
// measured shortfall keeps it from getting worse). Layer 1 holds more than
// the banners, so the check that must pass is the truth's: where the
// ray-traced visible truth's tint moves by at least 0.02 from E0 to E0 +
// E1, the renderer's moves the same way from one layer to two.
TEST_CASE(
    "radiosity accuracy: atrium's banners tint the floor and the columns before them more with two "
    "layers",
    "[radiosity-accuracy]") {
    const Scene scene = load_scene("atrium");
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    // The scene's lengths: a 1 m radius projects to a few pixels at the
    // banners.
    const RenderSettings base = with_scene_lengths(accuracy_settings(RadiosityMethod::area), scene);
    FloatImage irradiance[2];
    FloatImage depth_layer0;
    for (const int layers : {1, 2}) {
        RenderSettings settings = base;
        settings.radiosity.layers = layers;
        Renderer renderer(scene, settings, loader);
        for (int frame = 0; frame < 8; ++frame) renderer.render(scene.default_camera);
        depth_layer0 = renderer.read_pass_output("gbuffer-depth-layer0");
        irradiance[layers - 1] = renderer.read_pass_output("radiosity-irradiance-layer0");
    }
    const struct {
        BannerRegion region;
        const char* name;
        int min_pixels;
    } regions[] = {{BannerRegion::floor, "floor", 20}, {BannerRegion::column_sides, "column", 10}};
    for (const auto& region : regions) {
        std::array<double, 5> tint[2];
        std::array<int, 5> counts[2];
        for (int l = 0; l < 2; ++l)
            tint[l] = banner_tint(irradiance[l], depth_layer0, scene.default_camera, base,
                                  region.region, counts[l]);
        // What the layers hold says how the tint should move: the visible
        // truth's tint with one layer (E0) and with two (E0 + E1).
        const VisibleTint truth = banner_visible_tint(scene, depth_layer0, base, region.region);
        for (int i = 0; i < 5; ++i) {
            const auto k = std::size_t(i);
            INFO(region.name << ", banner " << i << ": " << counts[0][k] << " pixels, tint 1 layer "
                             << tint[0][k] << ", 2 layers " << tint[1][k] << "; visible truth E0 "
                             << truth.one_layer[k] << ", E0 + E1 " << truth.two_layers[k]);
            WARN("atrium banner " << i << ": " << region.name << " tint toward it, 1 layer "
                                  << tint[0][k] << ", 2 layers " << tint[1][k] << " ("
                                  << counts[0][k] << " pixels); visible truth E0 "
                                  << truth.one_layer[k] << ", E0 + E1 " << truth.two_layers[k]);
            // The camera sees neither side of the middle column (banner 2).
            if (region.region == BannerRegion::column_sides && i == 2) {
                CHECK(counts[0][k] == 0);
                continue;
            }
            REQUIRE(counts[0][k] > region.min_pixels);
            REQUIRE(counts[1][k] > region.min_pixels);
            // Where the second layer's light moves the truth's tint clearly,
            // the renderer's second layer moves it the same way.
            const double truth_change = truth.two_layers[k] - truth.one_layer[k];
            if (std::abs(truth_change) >= 0.02)
                CHECK((tint[1][k] - tint[0][k]) * truth_change > 0.0);
            // Target: two layers tint more, i.e. (1 layer - 2 layers) <= 0.
            targets().check_at_most(fmt::format("atrium/banner {}", i),
                                    fmt::format("{} tint, 1 layer - 2 layers", region.name),
                                    "8 frames", tint[0][k] - tint[1][k], 0.0);
        }
    }
    targets().write();
}

}  // namespace deepgi::test
