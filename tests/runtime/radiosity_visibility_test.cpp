// The radiosity gather's visibility test on a geometry whose answer is known:
// an emitting wall that a board hides from the floor in front of it, and the
// same wall behind thinner occluders.
#include "form_factor_oracle.hpp"
#include "sao_reference.hpp"
#include "sao_test_support.hpp"
#include "support/targets.hpp"
#include "test_scenes.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

namespace deepgi::test {
namespace {

// What stands between the floor and the emitting wall of wall_behind_board().
enum class Occluder {
    board,       // a closed box 0.1 m deep
    thin_board,  // a closed box 1 cm deep: thinner than any step of the march
    open_sheet,  // one quad facing the camera: an open mesh, no back face
    beam,        // a closed box 0.2 m deep held above the wall's top: it hides
                 // nothing from the floor, only space below it from the camera
};

// Everything black but an emitting wall (z = -8, x in [-2, 2], y in [0, 0.5],
// facing +z, radiance 1) standing on a floor (y = 0). A board 0.8 m high and
// 6 m wide (0.1 m thick by default, z in [-6.05, -5.95]) stands before the
// wall: from any floor point in front of the board (z > -5.95) the segment to
// any point of the wall crosses the board's plane below 0.5 m, inside the
// board, so the wall is hidden there; the floor behind the board (z < -6.9)
// sees all of it. The camera, 10 m up and looking down, sees the floor on
// both sides, the board and the wall's face, so layer 0 holds the wall. With
// everything else black, the wall is the only light the gather can find. The
// scene's bounds, and so every `auto` length, are the same for every
// occluder.
Scene wall_behind_board(Occluder occluder = Occluder::board) {
    Scene scene;
    scene.name = "test-wall-behind-board";
    SceneBuilder builder;
    const int black = builder.add_material({0.0f, 0.0f, 0.0f});
    const int emitter = builder.add_material({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f});
    builder.add_quad({-6, 0, 4}, {6, 0, 4}, {6, 0, -12}, {-6, 0, -12}, {0, 1, 0}, black);
    if (occluder == Occluder::beam) {
        builder.add_box({0.0f, 1.3f, -6.0f}, {3.0f, 0.3f, 0.1f}, black);
    } else if (occluder == Occluder::open_sheet) {
        builder.add_quad({-3.0f, 0.0f, -6.0f}, {3.0f, 0.0f, -6.0f}, {3.0f, 0.8f, -6.0f},
                         {-3.0f, 0.8f, -6.0f}, {0, 0, 1}, black);
    } else {
        const float half_depth = occluder == Occluder::thin_board ? 0.005f : 0.05f;
        builder.add_box({0.0f, 0.4f, -6.0f}, {3.0f, 0.4f, half_depth}, black);
    }
    builder.add_quad({-2.0f, 0.0f, -8.0f}, {2.0f, 0.0f, -8.0f}, {2.0f, 0.5f, -8.0f},
                     {-2.0f, 0.5f, -8.0f}, {0, 0, 1}, emitter);
    builder.finish(scene);
    scene.default_camera = camera_at_origin();
    scene.default_camera.position = glm::vec3(0.0f, 10.0f, 2.0f);
    scene.default_camera.pitch = -std::atan(10.0f / 7.0f);  // towards (0, 0, -5)
    scene.camera_path.keys = {scene.default_camera};
    return scene;
}

// The wall's irradiance at floor point p (normal +y) within `radius`, with no
// occlusion: the integral of cos_x cos_y / d^2 over the wall, by the midpoint
// rule on 2.5 cm cells.
double wall_irradiance(glm::vec3 p, float radius) {
    return floor_from_wall_form_factor(p, radius, {-2.0, 2.0}, {0.0, 0.5}, -8.0, 160, 20);
}

// Mean E of layer 0 over a floor region, after 8 still frames.
struct Region {
    double e = 0.0, oracle = 0.0;  // sums of E and of the unoccluded form factor
    int count = 0, dark = 0;       // pixels, and those whose E is exactly 0
    double mean() const { return e / count; }
    double oracle_mean() const { return oracle / count; }
};

// The floor before the board (z in (-5.7, -3)) and behind it (z in (-7.8,
// -6.9)), within 1.5 m of the middle, 192x108, one bounce, radius `radius`,
// with `steps` points of the visibility test (0: none), solids `thickness`
// deep behind open meshes (the settings' default, 0.2 m, unless given).
std::pair<Region, Region> floor_irradiance(const Scene& scene, const ShaderLoader& loader,
                                           int steps, float radius, float thickness = 0.0f) {
    RenderSettings settings = small_settings(192, 108);
    if (thickness > 0.0f) settings.ao.thickness = thickness;
    settings.radiosity.rho_prop = 0.0f;
    settings.radiosity.radius = radius;
    settings.radiosity.visibility_steps = steps;
    Renderer renderer(scene, settings, loader);
    for (int frame = 0; frame < 8; ++frame) renderer.render(scene.default_camera);
    const FloatImage e = renderer.read_pass_output("radiosity-irradiance-layer0");
    const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
    Region front, behind;
    for (int y = 0; y < e.height; ++y) {
        for (int x = 0; x < e.width; ++x) {
            if (depth.at(x, y, 0) <= 0.0f) continue;
            const glm::vec3 p = world_point(depth, scene.default_camera, settings, x, y);
            if (std::abs(p.y) > 0.01f || std::abs(p.x) > 1.5f) continue;
            Region* region = nullptr;
            if (p.z < -3.0f && p.z > -5.7f) region = &front;
            if (p.z < -6.9f && p.z > -7.8f) region = &behind;
            if (!region) continue;
            region->e += e.at(x, y, 0);
            region->oracle += wall_irradiance(p, radius);
            region->dark += e.at(x, y, 0) == 0.0f;
            ++region->count;
        }
    }
    return {front, behind};
}

// What each test below begins with: a GL context and the build's shaders,
// with which it measures the floor of a wall_behind_board() scene, always
// gathering within 6 m.
struct WallTest {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    static constexpr float radius = 6.0f;

    std::pair<Region, Region> measure(const Scene& scene, int steps, float thickness = 0.0f) const {
        return floor_irradiance(scene, loader, steps, radius, thickness);
    }
    // Without the visibility test, with enough pixels before the occluder
    // and behind it to measure.
    std::pair<Region, Region> measure_without_test(const Scene& scene) const {
        const std::pair<Region, Region> regions = measure(scene, 0);
        REQUIRE(regions.first.count > 200);
        REQUIRE(regions.second.count > 60);
        return regions;
    }
};

TEST_CASE("radiosity: a wall hidden behind a board adds nothing with the visibility test",
          "[radiosity]") {
    const WallTest test;
    const Scene scene = wall_behind_board();
    Region front[2], behind[2];  // [visibility off, on]
    for (int on = 0; on < 2; ++on) {
        // Eight steps along segments up to 5.4 m: 0.68 m apart, about the
        // depth of the floor strip behind the board that the board hides
        // from the camera, so a step behind the board mostly lands inside it.
        std::tie(front[on], behind[on]) = test.measure(scene, on ? 8 : 0);
    }
    for (int on = 0; on < 2; ++on) {
        REQUIRE(front[on].count > 200);
        REQUIRE(behind[on].count > 60);
    }
    const double front_off = front[0].e / front[0].count;
    const double front_on = front[1].e / front[1].count;
    const double behind_off = behind[0].e / behind[0].count;
    const double behind_on = behind[1].e / behind[1].count;
    WARN("floor before the board, mean E: "
         << front_off << " without the test (unoccluded form "
         << "factor " << front[0].oracle / front[0].count << "), " << front_on << " with it, "
         << front[1].dark << " of " << front[1].count
         << " pixels dark; floor behind the board: " << behind_off << " without, " << behind_on
         << " with (form factor " << behind[0].oracle / behind[0].count << ")");
    // Without the test the gather sums the hidden wall, as the unoccluded
    // form factor says (a coarse estimate: few of the 19 taps land on it).
    CHECK(front_off > 0.75 * front[0].oracle / front[0].count);
    CHECK(front_off < 1.25 * front[0].oracle / front[0].count);
    // With it, the hidden wall adds next to nothing: nearly every pixel
    // before the board is exactly dark. Not all: from the far end of the
    // region a segment's steps, 0.68 m apart, can straddle the strip behind
    // the board that the board hides from the camera, which is 0.7 m deep at
    // the floor and shallower higher up, so no step lands inside the board
    // (measured: 413 of 428 pixels dark, 3.3% of the light left).
    CHECK(front[1].dark >= 0.95 * front[1].count);
    CHECK(front_on <= 0.05 * front_off);
    // Where nothing hides the wall the test removes nothing.
    CHECK(behind_off > 0.75 * behind[0].oracle / behind[0].count);
    CHECK(behind_on == Approx(behind_off).epsilon(1e-6));
}

TEST_CASE(
    "radiosity: the visibility test hides the wall behind a 1 cm board as behind a 10 cm one, "
    "and behind an open sheet nearly as well",
    "[radiosity]") {
    const WallTest test;
    // The target, as for the 10 cm board: behind the occluder the wall adds
    // at most 5% of its unoccluded light with 8 steps. A closed board 1 cm
    // deep meets it: its solid is taken two steps deep (1.1 m to 1.4 m
    // along these segments), which covers the strip the board hides from
    // the camera. An open sheet, one quad with no back face behind it, is
    // taken `--ao-thickness` deep (0.2 m here, the settings' default) and at
    // least two steps, as the boards: taken 0.2 m deep only, it let 70% of
    // the light through with 8 steps, since a segment's steps passed behind
    // the sheet further than that. It left 3.9% with 8 steps (at 192x108
    // after 8 frames) until the gather's disk widened towards the ball's
    // projection (docs/radiosity.md, "The screen disk"): the segments now
    // reach nearer points of the wall, longer segments whose steps straddle
    // the strip the sheet hides from the camera more often, and it leaves
    // 5.3%, a miss listed with its regression bound
    // (docs/radiosity-studies.md, "Thin occluders").
    spiral::test::TargetTable targets(
        "radiosity-visibility-targets.md",
        {{"open sheet/hidden light left/8 steps",
          {0.058, "0.0528 at 192x108 after 8 frames, the disk widened at most 1.5x"}}});
    const auto leak = [](const Region& on, const Region& off) { return on.mean() / off.mean(); };

    const Scene thin = wall_behind_board(Occluder::thin_board);
    const auto [thin_off, thin_behind_off] = test.measure_without_test(thin);
    const auto [thin_on, thin_behind_on] = test.measure(thin, 8);
    targets.check_at_most("1 cm board", "hidden light left", "8 steps", leak(thin_on, thin_off),
                          0.05);
    CHECK(thin_on.dark >= 0.95 * thin_on.count);
    CHECK(thin_behind_on.mean() == Approx(thin_behind_off.mean()).epsilon(1e-6));

    const Scene sheet = wall_behind_board(Occluder::open_sheet);
    const auto [sheet_off, sheet_behind_off] = test.measure_without_test(sheet);
    // Without the test the sheet's floor gets the wall's unoccluded light,
    // as the board's does.
    CHECK(sheet_off.mean() > 0.75 * sheet_off.oracle_mean());
    CHECK(sheet_off.mean() < 1.25 * sheet_off.oracle_mean());
    std::vector<double> sheet_leak;  // 4, 8, 16 steps
    std::vector<int> sheet_dark;
    for (int steps : {4, 8, 16}) {
        const auto [on, behind_on] = test.measure(sheet, steps);
        sheet_leak.push_back(leak(on, sheet_off));
        sheet_dark.push_back(on.dark);
        // Where nothing hides the wall the test removes nothing.
        CHECK(behind_on.mean() == Approx(sheet_behind_off.mean()).epsilon(1e-6));
    }
    targets.check_at_most("open sheet", "hidden light left", "8 steps", sheet_leak[1], 0.05);
    // Two steps are deep enough: a solid taken 2 m deep (more than two
    // steps of these segments) hides no more.
    const Region deep_on = test.measure(sheet, 8, 2.0f).first;
    const double deep_leak = leak(deep_on, sheet_off);
    CHECK(deep_leak < 0.1);
    CHECK(deep_leak == Approx(sheet_leak[1]).margin(0.005));
    targets.write();
    WARN(
        "share of the hidden wall's light left on the floor before the occluder: 1 cm board, 8 "
        "steps: "
        << leak(thin_on, thin_off) << " (" << thin_on.dark << " of " << thin_on.count
        << " pixels dark); open sheet, 4, 8, 16 steps: " << sheet_leak[0] << ", " << sheet_leak[1]
        << ", " << sheet_leak[2] << " (" << sheet_dark[0] << ", " << sheet_dark[1] << ", "
        << sheet_dark[2] << " of " << sheet_off.count
        << " pixels dark); open sheet taken 2 m deep, 8 steps: " << deep_leak);
    // More steps land more often inside the sheet's solid: with 16 the
    // leak is within the target.
    CHECK(sheet_leak[1] < sheet_leak[0]);
    CHECK(sheet_leak[2] <= sheet_leak[1]);
    CHECK(sheet_leak[2] <= 0.05);
}

TEST_CASE(
    "radiosity: the visibility test keeps the light of segments that pass below a beam, hidden "
    "only from the camera",
    "[radiosity]") {
    const WallTest test;
    // The beam spans y in [1.0, 1.6] and the wall ends at 0.5, so no segment
    // from the floor to the wall meets it: the floor before it sees the whole
    // wall, and the unoccluded form factor is the oracle. From the camera,
    // 10 m up, the beam hides a wedge of space below and behind it that most
    // of these segments cross (a point 0.1 m above the floor is hidden for
    // z below about -6.6). A solid taken two steps deep behind the beam's
    // front without asking how the segment got there hid up to half of that
    // light (measured: 0.47 of it kept with 4 steps, 0.92 with 8, all with 16).
    const Scene scene = wall_behind_board(Occluder::beam);
    const Region off = test.measure(scene, 0).first;
    REQUIRE(off.count > 200);
    CHECK(off.mean() > 0.75 * off.oracle_mean());
    CHECK(off.mean() < 1.25 * off.oracle_mean());
    for (int steps : {4, 8, 16}) {
        const Region on = test.measure(scene, steps).first;
        REQUIRE(on.count == off.count);
        INFO(steps << " steps: " << on.mean() / off.mean() << " of the light kept");
        CHECK(on.mean() >= 0.99 * off.mean());
    }
}

}  // namespace
}  // namespace deepgi::test
