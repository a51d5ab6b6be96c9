// The march's solids behind a thin beam over a floor, against the ambient
// visibility of that geometry integrated on the CPU from its definition.
#include "sao_test_support.hpp"
#include "support/targets.hpp"
#include "test_scenes.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

namespace deepgi::test {
namespace {

// A square beam 6 cm thick and 6 m long (x), its axis at height 0.35 m and
// z = -6.5, over a floor (y = 0). The camera, 2 m up at z = -4.5 and looking
// down at 45 degrees, sees the floor on both sides of the beam and hides a
// wedge of space below and behind it. The view ray crosses at most 8.5 cm of
// the beam, less than the two steps (19 cm at r = 1.5 m) every solid is
// taken to be at least.
constexpr glm::vec3 beam_centre{0.0f, 0.35f, -6.5f};
constexpr glm::vec3 beam_half{3.0f, 0.03f, 0.03f};
constexpr float beam_radius = 1.5f;

Scene beam_over_floor() {
    Scene scene;
    scene.name = "test-beam-over-floor";
    SceneBuilder builder;
    const int white = builder.add_material({0.8f, 0.8f, 0.8f});
    builder.add_quad({-6, 0, 4}, {6, 0, 4}, {6, 0, -12}, {-6, 0, -12}, {0, 1, 0}, white);
    builder.add_box(beam_centre, beam_half, white);
    builder.finish(scene);
    scene.default_camera = camera_at_origin();
    scene.default_camera.position = glm::vec3(0.0f, 2.0f, -4.5f);
    scene.default_camera.pitch = glm::radians(-45.0f);
    scene.camera_path.keys = {scene.default_camera};
    return scene;
}

// Distance along unit direction d from p to the beam, or -1 if the ray
// misses it (the slab test on the axis-aligned box).
float beam_hit(glm::vec3 p, glm::vec3 d) {
    float near = 0.0f, far = 1.0e30f;
    for (int axis = 0; axis < 3; ++axis) {
        const float lo = beam_centre[axis] - beam_half[axis];
        const float hi = beam_centre[axis] + beam_half[axis];
        if (std::abs(d[axis]) < 1.0e-9f) {
            if (p[axis] < lo || p[axis] > hi) return -1.0f;
            continue;
        }
        float t0 = (lo - p[axis]) / d[axis], t1 = (hi - p[axis]) / d[axis];
        if (t0 > t1) std::swap(t0, t1);
        near = std::max(near, t0);
        far = std::min(far, t1);
    }
    return near <= far ? near : -1.0f;
}

// The oracle: AV = 1 - mean f(d), f(d) = 1 - d^2 / r^2 for the first hit
// within r, over cosine-weighted directions about the floor's normal (+y),
// by the midpoint rule on a 96x96 grid of the disk's polar square (Malley's
// method). Only the beam can be hit from the floor.
double floor_visibility(glm::vec3 p, float radius) {
    constexpr int n = 96;
    double occlusion = 0.0;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const float u = (float(i) + 0.5f) / n, v = (float(j) + 0.5f) / n;
            const float s = std::sqrt(u), phi = 6.2831853f * v;
            const glm::vec3 d(s * std::cos(phi), std::sqrt(std::max(0.0f, 1.0f - u)),
                              s * std::sin(phi));
            const float t = beam_hit(p, d);
            if (t >= 0.0f && t < radius)
                occlusion += 1.0 - double(t) * t / (double(radius) * radius);
        }
    }
    return 1.0 - occlusion / (n * n);
}

// Every solid is taken at least two steps deep, so that a ray crossing a part
// thinner than the steps lands inside it (docs/deep-sao.md, "The march").
// Behind a beam thinner than that along the view ray, the allowance also
// fills space the beam hides only from the camera, and rays from the floor
// that pass there are taken as hits: the march is darker than the oracle on
// both sides of the beam (measured: by 0.039 before it and 0.020 behind it).
// Asking how the ray left the camera's sight, as the radiosity visibility
// test does, brings these to 0.013 and 0.001 but makes ref-slab, ref-board,
// ref-bench and warehouse much worse (docs/deep-sao-studies.md, "The two
// steps' allowance"), so the allowance is kept: a known miss of 0.01, with
// regression bounds about 10% above the measured gaps.
TEST_CASE("sao: the march does not hide the space a beam hides only from the camera", "[march]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const Scene scene = beam_over_floor();
    RenderSettings settings = small_settings(320, 180);
    settings.ao.method = AoMethod::march;
    settings.ao.radius = beam_radius;
    Renderer renderer(scene, settings, loader);
    // The mean of the raw march over frames of a still camera: the temporal
    // sequence moves the rays and steps, so the mean converges to the march's
    // expectation.
    constexpr int frames = 32;
    FloatImage sum;
    for (int frame = 0; frame < frames; ++frame) {
        renderer.render(scene.default_camera);
        const FloatImage raw = renderer.read_pass_output("ao-raw");
        if (frame == 0)
            sum = raw;
        else
            for (std::size_t i = 0; i < sum.pixels.size(); ++i) sum.pixels[i] += raw.pixels[i];
    }
    const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
    // Floor pixels near the middle, before the beam (z in (-6.47, -5.5)) and
    // behind the strip of floor it hides (z in (-7.5, -6.9)).
    struct Region {
        double march = 0.0, oracle = 0.0;
        int count = 0;
    } front, behind;
    for (int y = 0; y < depth.height; ++y) {
        for (int x = 0; x < depth.width; ++x) {
            if (depth.at(x, y, 0) <= 0.0f) continue;
            const glm::vec3 p = world_point(depth, scene.default_camera, settings, x, y);
            if (std::abs(p.y) > 0.005f || std::abs(p.x) > 1.0f) continue;
            Region* region = nullptr;
            if (p.z > -6.47f && p.z < -5.5f) region = &front;
            if (p.z > -7.5f && p.z < -6.9f) region = &behind;
            if (!region) continue;
            region->march += sum.at(x, y, 0) / frames;
            region->oracle += floor_visibility(glm::vec3(p.x, 0.0f, p.z), beam_radius);
            ++region->count;
        }
    }
    spiral::test::TargetTable targets(
        "ao-march-beam-targets.md",
        {{"floor before the beam/gap to the oracle/32 frames",
          {0.043, "0.0393 measured at 320x180, r = 1.5 m, llvmpipe"}},
         {"floor behind the beam/gap to the oracle/32 frames",
          {0.0225, "0.0204 measured at 320x180, r = 1.5 m, llvmpipe"}}});
    for (const Region* region : {&front, &behind}) {
        REQUIRE(region->count > 100);
        const double march = region->march / region->count;
        const double oracle = region->oracle / region->count;
        INFO((region == &front ? "before" : "behind")
             << " the beam, " << region->count << " pixels: march " << march << ", oracle "
             << oracle);
        CHECK(oracle < 0.99);  // the beam occludes there, so the comparison means something
        targets.check_at_most(region == &front ? "floor before the beam" : "floor behind the beam",
                              "gap to the oracle", "32 frames", std::abs(march - oracle), 0.01);
        targets.write();
    }
}

}  // namespace
}  // namespace deepgi::test
