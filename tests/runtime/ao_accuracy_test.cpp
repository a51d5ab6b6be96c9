// Deep SAO against the ray-traced ambient visibility (Embree, the reference
// library): the accuracy targets of the estimator on the reference scenes and
// the built-in ones, at a small size so the suite stays fast on two cores.
// The truth is an independent Monte Carlo integral of the same definition
// (docs/reference.md); nothing here is a value recorded from the shader.
#include "deepgi/context.hpp"
#include "deepgi/reference.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "support/runtime_support.hpp"
#include "support/targets.hpp"
#include "support/textbook_camera.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace deepgi::test {
namespace {

// The size every figure of docs/deep-sao.md and the report is quoted at.
// Coarser pixels lose parts thinner than a pixel from the G-buffer while the
// reference's ray through the pixel centre still finds them: at 192x108 the
// march's bias misses on cornell and warehouse (docs/deep-sao.md).
constexpr int width = 320, height = 180;

RenderSettings accuracy_settings(int layers, AoMethod method = AoMethod::solid_angle) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.shadow_map_size = 64;
    settings.ao.layers = layers;
    settings.ao.method = method;
    settings.ao.bias = default_ao_bias(method);
    return settings;
}

struct Error {
    double mae = 0.0;
    double bias = 0.0;
    long long pixels = 0;
    long long open = 0;       // truth AV >= 0.9999: nothing within r
    long long open_dark = 0;  // of those, estimate below 0.99
    // Open pixels whose neighbours within `reach` pixels are all open too.
    // The truth is a Monte Carlo estimate: next to occluded pixels it reads 1
    // where an occluder's reach ends inside the pixel and none of its rays
    // found it, so the raw target takes the pixels whose 3x3 neighbourhood is
    // open. After the blur it takes those whose neighbours within the blur's
    // reach are open: next to occluded pixels the blur rightly averages
    // their occlusion in, as a blur of the truth would.
    long long open_core = 0;
    long long open_core_dark = 0;
};

// The raw estimate's neighbourhood (above) and the separable blur's reach.
constexpr int raw_reach = 1;
constexpr int blur_reach = SAO_TEST_BLUR_RADIUS;

// Whether every truth pixel within `reach` pixels (a square: the separable
// blur's two directions reach that far) is open.
bool open_around(const FloatImage& truth, int x, int y, int reach) {
    for (int v = std::max(0, y - reach); v <= std::min(truth.height - 1, y + reach); ++v) {
        for (int u = std::max(0, x - reach); u <= std::min(truth.width - 1, x + reach); ++u) {
            if (truth.at(u, v) < 0.9999f) return false;
        }
    }
    return true;
}

// Over the viewport (guard band excluded) where the rasteriser and the ray
// tracer see the same surface, as deepgi_compare_reference measures. The
// estimate is clamped to [0, 1] as compose uses it (the solid-angle AV is
// signed until then, sao.frag).
Error measure(const FloatImage& estimate, const FloatImage& raster_depth,
              const ReferenceImages& truth, int guard, int reach) {
    Error error;
    double sum_abs = 0.0, sum = 0.0;
    const FloatImage& traced = truth.depth_layer0;
    for (int y = guard; y < traced.height - guard; ++y) {
        for (int x = guard; x < traced.width - guard; ++x) {
            const float a = raster_depth.at(x, y), b = traced.at(x, y);
            if (!(a > 0.0f && b > 0.0f && std::abs(a - b) <= 1e-3f * b)) continue;
            const float value = std::clamp(estimate.at(x, y), 0.0f, 1.0f);
            const double e = double(value) - truth.ambient_visibility.at(x, y);
            sum_abs += std::abs(e);
            sum += e;
            ++error.pixels;
            if (truth.ambient_visibility.at(x, y) >= 0.9999f) {
                ++error.open;
                error.open_dark += value < 0.99f;
                if (open_around(truth.ambient_visibility, x, y, reach)) {
                    ++error.open_core;
                    error.open_core_dark += value < 0.99f;
                }
            }
        }
    }
    error.mae = sum_abs / double(error.pixels);
    error.bias = sum / double(error.pixels);
    return error;
}

// Frames a static camera renders for the accumulated figures: the first
// frame and eight after it, each with a new rotation (frame.cpp).
constexpr int accumulated_frames = 9;

// What each estimator must reach. The march and the solid angle keep the
// targets they were built to (MAE <= .03, |bias| <= .01 on both stages,
// accumulated over 9 still frames); gtao and bitmask are held to the same
// ones and reported where they miss; the thick spiral is held to the
// stricter ones it was built to: MAE <= .015 and |bias| <= .005
// on the first frame, MAE <= .01 after 64 still frames.
struct Targets {
    double mae_first = 0.03, bias_first = 0.01;
    double mae_accumulated = 0.03, bias_accumulated = 0.01;
    int frames = accumulated_frames;
};

Targets targets_of(AoMethod method) {
    if (method == AoMethod::spiral_thick) return {0.015, 0.005, 0.01, 0.01, 64};
    return {};
}

struct StageErrors {
    Error one_layer, two_layers;
    Error raw_two_layers;  // before the blur (and before the temporal filter's history)
};

struct SceneErrors {
    StageErrors first;        // the first frame
    StageErrors accumulated;  // after accumulated_frames static frames
};

ReferenceImages trace_truth(const Scene& scene) {
    ReferenceSettings reference;
    reference.render = accuracy_settings(2);
    // A standard error of 0.006 per pixel adds about 0.005 to a mean absolute
    // error and nothing to the mean bias (the estimate is unbiased).
    reference.rays.min_rays = 512;
    reference.rays.target_error = 0.006;
    reference.threads = 2;
    const RayScene rays(scene);
    return render_reference(rays, scene.default_camera, reference);
}

SceneErrors measure_scene(const Scene& scene, const ReferenceImages& truth, AoMethod method,
                          int frames) {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    SceneErrors errors;
    for (int layers : {1, 2}) {
        const RenderSettings settings = accuracy_settings(layers, method);
        Renderer renderer(scene, settings, loader);
        const int guard = frame_layout(settings).guard;
        for (int frame = 1; frame <= frames; ++frame) {
            renderer.render(scene.default_camera);
            if (frame != 1 && frame != frames) continue;
            StageErrors& stage = frame == 1 ? errors.first : errors.accumulated;
            const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
            const Error error =
                measure(renderer.read_pass_output("ao-blurred"), depth, truth, guard, blur_reach);
            (layers == 1 ? stage.one_layer : stage.two_layers) = error;
            if (layers == 2)
                stage.raw_two_layers =
                    measure(renderer.read_pass_output("ao-raw"), depth, truth, guard, raw_reach);
        }
    }
    return errors;
}

// Targets not met yet, as "method/scene/target/stage", with the regression
// bound each must still keep: taken from the measured value (about 10% above
// it, two more pixels for counts of a few), not a target. Every target not
// listed is a hard check at its own value. The table of all targets goes to
// ao-accuracy-targets.md, which the ctest entry
// "deepgi_ao_accuracy_targets_missed" prints (support/targets.hpp).
spiral::test::TargetTable& targets() {
    static spiral::test::TargetTable table(
        "ao-accuracy-targets.md",
        {
            // The solid angle sees only what the layers store: occluders hidden
            // from both (reference split: 0.025 on average on warehouse, more
            // than its whole bias) are missing, and creases are noisy in one
            // frame (docs/deep-sao.md).
            {"solid-angle/cornell/mae/first", {0.037, "measured 0.0334"}},
            {"solid-angle/warehouse/mae/first", {0.036, "measured 0.0322"}},
            {"solid-angle/warehouse/bias/first", {0.024, "measured +0.0213"}},
            {"solid-angle/warehouse/bias/accumulated", {0.023, "measured +0.0203"}},
            // The march where a ray leaving the side of one of atrium's
            // pillars passes, 0.43 m out, through the frustum of a pixel at
            // the edge of an arch's underside (layer 1), whose solid fills the
            // whole pixel: a convex edge the convex-edge test cannot see, as
            // X's surface is not one of its faces (docs/deep-sao.md, "The
            // convex-edge test").
            {"march/atrium/open/first", {3.0, "measured 1 pixel"}},
            // The thick spiral against the stricter targets it was built to
            // (first frame MAE <= .015 and |bias| <= .005, MAE <= .01 after 64
            // still frames): a sector's union of a few taps' bands is too dark
            // where an occluder fills part of it and too bright where its taps
            // miss one (docs/deep-sao.md, "The thick spiral"); 64 frames average
            // its noise but not that bias.
            {"spiral-thick/ref-crease/bias/first", {0.0099, "measured -0.0090"}},
            {"spiral-thick/ref-board/bias/first", {0.0070, "measured -0.0064"}},
            {"spiral-thick/ref-bench/mae/accumulated", {0.0160, "measured 0.0146"}},
            {"spiral-thick/cornell/mae/first", {0.0353, "measured 0.0321"}},
            {"spiral-thick/cornell/mae/accumulated", {0.0344, "measured 0.0313"}},
            {"spiral-thick/atrium/bias/first", {0.0056, "measured +0.00504"}},
            {"spiral-thick/warehouse/mae/first", {0.0267, "measured 0.0242"}},
            {"spiral-thick/warehouse/bias/first", {0.0133, "measured +0.0120"}},
            {"spiral-thick/warehouse/mae/accumulated", {0.0253, "measured 0.0229"}},
            {"spiral-thick/warehouse/bias/accumulated", {0.0126, "measured +0.0115"}},
            // The slice estimators (docs/deep-sao.md, "Slice estimators"),
            // reported beside the others at the defaults (2 slices x 8 steps,
            // thickness 0.2 m), with the reference's falloff: too bright on
            // cornell and warehouse, whose creases and shelves their 8 steps
            // per side and 2 slices sample coarsely.
            {"gtao/cornell/bias/first", {0.0252, "measured +0.0229"}},
            {"gtao/cornell/bias/accumulated", {0.0249, "measured +0.0226"}},
            {"bitmask/cornell/bias/first", {0.0310, "measured +0.0281"}},
            {"bitmask/cornell/bias/accumulated", {0.0307, "measured +0.0279"}},
            {"gtao/warehouse/bias/first", {0.0178, "measured +0.0162"}},
            {"gtao/warehouse/bias/accumulated", {0.0179, "measured +0.0163"}},
            {"bitmask/warehouse/bias/first", {0.0232, "measured +0.0211"}},
            {"bitmask/warehouse/bias/accumulated", {0.0233, "measured +0.0211"}},
        });
    return table;
}

// A target `value <= limit`: a hard check at the limit where met, the
// regression bound above where listed as missed.
void check_target(const std::string& name, const std::string& target, const std::string& stage,
                  double value, double limit) {
    targets().check_at_most(name, target, stage, value, limit);
}

void check_stage(const std::string& name, const std::string& stage, const StageErrors& errors,
                 double mae_limit, double bias_limit) {
    const Error& two = errors.two_layers;
    const Error& one = errors.one_layer;
    INFO(name << ", " << stage << ": two layers MAE " << two.mae << " bias " << two.bias
              << "; one layer MAE " << one.mae << " bias " << one.bias << "; " << two.pixels
              << " pixels; open pixels below 0.99, all / in open surroundings: before the blur "
              << errors.raw_two_layers.open_dark << " of " << two.open << " / "
              << errors.raw_two_layers.open_core_dark << " of " << errors.raw_two_layers.open_core
              << ", after " << two.open_dark << " / " << two.open_core_dark << " of "
              << two.open_core);
    REQUIRE(two.pixels > width * height / 4);
    check_target(name, "mae", stage, two.mae, mae_limit);
    check_target(name, "bias", stage, std::abs(two.bias), bias_limit);
    // The second layer only adds occluders; it must not cost accuracy.
    check_target(name, "two-vs-one", stage, two.mae - one.mae, 0.0);
    // Surfaces with nothing within r stay open in the estimate itself, and
    // after the blur wherever no occluded pixel lies within its reach.
    check_target(name, "open", stage, double(errors.raw_two_layers.open_core_dark), 0.0);
    check_target(name, "open-blurred", stage, double(two.open_core_dark), 0.0);
    // On the bench behind the posts layer 1 sees occluders layer 0 cannot:
    // two layers' MAE at least 5e-4 below one layer's (a target row, so that
    // an estimator that layer 1 darkens further is reported, not hidden).
    if (name.ends_with("/ref-bench"))
        check_target(name, "layer-1-gain", stage, two.mae - one.mae + 5e-4, 0.0);
}

}  // namespace

TEST_CASE("ao accuracy: blurred deep SAO estimates the ray-traced visibility on every scene",
          "[ao-accuracy]") {
    const auto name = GENERATE(as<std::string>{}, "ref-crease", "ref-slab", "ref-board",
                               "ref-bench", "cornell", "atrium", "warehouse");
    const Scene scene = load_scene(name);
    const ReferenceImages truth = trace_truth(scene);
    for (AoMethod method : {AoMethod::spiral_thick, AoMethod::solid_angle, AoMethod::march,
                            AoMethod::gtao, AoMethod::bitmask}) {
        // Keys of short_of_target() and the messages name the method first.
        const std::string key = std::string(to_string(method)) + "/" + name;
        const Targets targets = targets_of(method);
        const SceneErrors errors = measure_scene(scene, truth, method, targets.frames);
        check_stage(key, "first", errors.first, targets.mae_first, targets.bias_first);
        check_stage(key, "accumulated", errors.accumulated, targets.mae_accumulated,
                    targets.bias_accumulated);
    }
    targets().write();
}

}  // namespace deepgi::test

namespace deepgi::test {
namespace {

// Where the ray tracer leaves the object a stored surface belongs to: the
// nearest back face at or behind `depth` along the camera ray (t is linear
// depth for a direction of unit depth; 0: none), and the front faces it
// stepped past on the way. Faces that touch (a box resting on a shelf: its
// bottom, a back face, on the shelf's top, a front face) lie at the same t,
// and which of them the tracer reports there is arbitrary.
struct TracedBackFace {
    float back = 0.0f;
    std::vector<float> front_faces;
};

TracedBackFace trace_back_face(const RayScene& rays, glm::vec3 eye, glm::vec3 direction,
                               float depth) {
    TracedBackFace traced;
    float t_near = depth * (1.0f - 1e-5f);  // a back face coincident with the surface counts
    for (int guard = 0; guard < 1024; ++guard) {
        const RayScene::Hit hit = rays.intersect(eye, direction, t_near, 1e30f);
        if (!hit.hit) break;
        if (glm::dot(hit.normal, direction) > 0.0f) {
            traced.back = hit.distance;
            break;
        }
        traced.front_faces.push_back(hit.distance);
        t_near = std::nextafter(hit.distance, 1e30f) + hit.distance * 1e-6f;
    }
    return traced;
}

}  // namespace

// The back-face pass against an independent ray tracer: through every pixel
// centre with a stored surface, from that surface (so whatever the layer-1
// generator stored), the nearest back face the tracer finds.
TEST_CASE("ao accuracy: the march's back-face depth is where the ray tracer leaves each object",
          "[ao-accuracy]") {
    const auto name = GENERATE(as<std::string>{}, "ref-bench", "cornell", "warehouse");
    const Scene scene = load_scene(name);
    const RenderSettings settings = accuracy_settings(2, AoMethod::march);
    HeadlessContext context;
    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
    renderer.render(scene.default_camera);

    const Camera& camera = scene.default_camera;
    // The textbook camera (support/textbook_camera.hpp), not the library's.
    const TextbookCamera textbook = textbook_camera(camera, settings);
    const glm::vec3 eye = textbook.eye;
    const RayScene rays(scene);
    for (int layer = 0; layer < 2; ++layer) {
        const FloatImage depth =
            renderer.read_pass_output(fmt::format("gbuffer-depth-layer{}", layer));
        const FloatImage back =
            renderer.read_pass_output(fmt::format("backface-depth-layer{}", layer));
        std::vector<float> errors;  // relative; 1 where only one of the two has a back face
        int with_back_face = 0;
        for (int y = 0; y < depth.height; ++y) {
            for (int x = 0; x < depth.width; ++x) {
                if (!(depth.at(x, y) > 0.0f)) continue;
                const glm::vec3 direction = textbook_to_world(
                    textbook, textbook_camera_ray(textbook, float(x) + 0.5f, float(y) + 0.5f));
                const TracedBackFace traced = trace_back_face(rays, eye, direction, depth.at(x, y));
                const float rasterised = back.at(x, y);
                with_back_face += traced.back > 0.0f;
                auto relative = [&](float t) { return std::abs(rasterised - t) / t; };
                float error = 0.0f;
                if (traced.back > 0.0f && rasterised > 0.0f)
                    error = relative(traced.back);
                else if ((traced.back > 0.0f) != (rasterised > 0.0f))
                    error = 1.0f;
                // At touching faces the rasteriser keeps the back face the
                // tracer may have reported as the front face at the same t.
                if (rasterised > 0.0f) {
                    for (float t : traced.front_faces) error = std::min(error, relative(t));
                }
                errors.push_back(error);
            }
        }
        REQUIRE(errors.size() > 100);
        std::sort(errors.begin(), errors.end());
        const double agree =
            double(std::upper_bound(errors.begin(), errors.end(), 1e-3f) - errors.begin()) /
            double(errors.size());
        INFO(name << ", layer " << layer << ": " << errors.size() << " surface pixels, "
                  << with_back_face << " with a traced back face; median relative error "
                  << errors[errors.size() / 2] << ", within 1e-3: " << agree);
        CHECK(errors[errors.size() / 2] < 1e-5f);
        CHECK(agree > 0.99);
        // Most of layer 0 is closed boxes (the walls and floors are open).
        if (layer == 0) CHECK(with_back_face > int(errors.size()) / 10);
    }
}

}  // namespace deepgi::test
