// Scene scale: lengths left at `auto` follow the scene (docs/deepgi.md,
// "Scene scale"), so a scene drawn at another scale gives the same image,
// and the millimetre-unit 2CylinderEngine sample gets AO with default
// lengths.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/settings.hpp"
#include "deepgi/shader_loader.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace deepgi {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 192;
constexpr int kHeight = 108;
constexpr int kFrames = 9;

Scene load_engine() {
    const fs::path path =
        fs::path(DEEPGI_SAMPLE_MODELS) / "2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
    INFO(path.string() << " is part of assimp-testmodels (scripts/install-deps.sh)");
    REQUIRE(fs::exists(path));
    return load_gltf_scene(path);
}

// Every length of the scene times s: positions, bounds, cameras, the light's
// position and range. A point or spot light's intensity falls with the
// inverse square of the distance, so it is scaled by s^2 to light the scaled
// scene alike; a directional light's irradiance does not depend on distance.
Scene scaled(Scene scene, float s) {
    for (Vertex& vertex : scene.vertices) vertex.position *= s;
    scene.bounds.min *= s;
    scene.bounds.max *= s;
    auto scale_camera = [s](Camera& camera) {
        camera.position *= s;
        camera.near_plane *= s;
    };
    scale_camera(scene.default_camera);
    for (Camera& key : scene.camera_path.keys) scale_camera(key);
    scene.key_light.position *= s;
    scene.key_light.range *= s;
    if (scene.key_light.kind != LightKind::directional) scene.key_light.intensity *= s * s;
    return scene;
}

// Default settings at the test size, with every length `auto`, as the
// command line leaves them.
RenderSettings auto_settings() {
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.shadow_map_size = 1024;
    return with_auto_lengths(settings);
}

std::vector<std::uint8_t> render_still(const Scene& scene, const RenderSettings& settings) {
    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
    for (int frame = 0; frame < kFrames; ++frame) renderer.render(scene.default_camera);
    return renderer.read_output_rgba8();
}

TEST_CASE("scene scale: the engine scaled by 1e-3 and 1e3 renders the image of scale 1",
          "[runtime][scale]") {
    HeadlessContext context;
    const Scene engine = load_engine();
    const RenderSettings settings = auto_settings();
    const std::vector<std::uint8_t> reference = render_still(engine, settings);
    for (float s : {1e-3f, 1e3f}) {
        const std::vector<std::uint8_t> image = render_still(scaled(engine, s), settings);
        REQUIRE(image.size() == reference.size());
        double sum = 0.0;
        int largest = 0;
        std::size_t beyond_two = 0, pixels = image.size() / 4;
        for (std::size_t p = 0; p < pixels; ++p) {
            int pixel_largest = 0;
            for (int c = 0; c < 3; ++c) {
                const int d = std::abs(int(image[4 * p + c]) - int(reference[4 * p + c]));
                sum += d;
                pixel_largest = std::max(pixel_largest, d);
            }
            largest = std::max(largest, pixel_largest);
            beyond_two += pixel_largest > 2;
        }
        const double mean = sum / double(3 * pixels);
        WARN("scale " << s << ": mean |difference| " << mean << " of 255, largest " << largest
                      << ", " << beyond_two << " of " << pixels << " pixels differ by > 2");
        // The same image up to float rounding, which moves a few 8-bit levels
        // where a tap or a shadow-map texel falls the other way: on average
        // below half a level, and more than 2 levels on at most 1% of pixels.
        CHECK(mean <= 0.5);
        CHECK(double(beyond_two) <= 0.01 * double(pixels));
    }
}

// Mean blurred AO (clamped to [0, 1], as compose uses it) over the viewport's
// pixels that show a surface.
double mean_surface_ao(const Scene& scene, const RenderSettings& settings) {
    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
    for (int frame = 0; frame < kFrames; ++frame) renderer.render(scene.default_camera);
    const FloatImage ao = renderer.read_pass_output("ao-blurred");
    const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
    const int gx = (depth.width - ao.width) / 2, gy = (depth.height - ao.height) / 2;
    double sum = 0.0;
    std::size_t count = 0;
    for (int y = 0; y < ao.height; ++y) {
        for (int x = 0; x < ao.width; ++x) {
            if (depth.at(x + gx, y + gy, 0) <= 0.0f) continue;
            sum += std::clamp(ao.at(x, y, 0), 0.0f, 1.0f);
            ++count;
        }
    }
    REQUIRE(count > std::size_t(ao.width * ao.height / 10));
    return sum / double(count);
}

TEST_CASE("scene scale: the 2CylinderEngine sample shows AO with default (auto) lengths",
          "[runtime][scale]") {
    HeadlessContext context;
    const Scene engine = load_engine();
    const RenderSettings automatic = auto_settings();
    RenderSettings metres = automatic;  // the lengths that were the defaults before `auto`
    metres.ao.radius = 0.5f;
    metres.ao.thickness = 0.2f;
    metres.radiosity.radius = 1.0f;
    metres.min_separation = 0.5f;
    const double with_auto = mean_surface_ao(engine, automatic);
    const double with_metres = mean_surface_ao(engine, metres);
    WARN("engine, blurred AO mean over its surfaces: auto " << with_auto << ", 0.5 m radius "
                                                            << with_metres);
    CHECK(with_auto < 0.97);
    CHECK(with_metres > 0.99);  // why auto is needed: 0.5 scene units is under a millimetre
}

TEST_CASE("scene scale: auto lengths are the rows' fractions of the bounding radius",
          "[runtime][scale]") {
    HeadlessContext context;
    Scene scene = make_builtin_scene("cornell");
    const float radius = scene_bounding_radius(scene);
    CHECK(radius == Approx(0.5f * glm::length(scene.bounds.max - scene.bounds.min)));
    const SceneScale scale = scene_scale(scene);
    CHECK(scale.bounding_radius == radius);
    CHECK(scale.smallest_extent == Approx(2.0f));  // the 2 m room
    RenderSettings settings = auto_settings();
    settings.ao.radius = 0.3f;  // explicit: kept
    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
    const RenderSettings& in_use = renderer.settings_in_use();
    CHECK(renderer.settings().radiosity.radius == auto_length);
    CHECK(in_use.ao.radius == 0.3f);
    // Cornell is as high as it is wide: the extent's cap leaves the radius
    // at its fraction of the bounding radius.
    for (const char* name : {"radiosity-radius", "min-separation", "ao-thickness"}) {
        const NumericSetting& row = *find_numeric_setting(name);
        INFO(name);
        CHECK(row.get(in_use) == Approx(row.scene_fraction * radius));
    }
    CHECK_THROWS_AS(parse_setting_value(*find_numeric_setting("ao-radius"), "-1"), InputError);
    CHECK(parse_setting_value(*find_numeric_setting("ao-radius"), "auto") == auto_length);
    // The exposure's auto is measured each frame, not resolved from the scene.
    CHECK(parse_setting_value(*find_numeric_setting("exposure"), "auto") == auto_length);
    RenderSettings automatic;
    automatic.exposure = auto_length;
    CHECK(resolve_auto_lengths(automatic, scale).exposure == auto_length);
    CHECK_THROWS_AS(parse_setting_value(*find_numeric_setting("guard-band"), "auto"), InputError);
}

TEST_CASE("scene scale: a refused length quotes the text given, and says when it is past a float",
          "[scene_scale][hardening]") {
    const NumericSetting& radius = *find_numeric_setting("ao-radius");
    CHECK_THROWS_WITH(parse_setting_value(radius, "-1"),
                      "--ao-radius must be a finite number of metres > 0, or auto, got '-1'");
    CHECK_THROWS_WITH(parse_setting_value(radius, "nan"),
                      "--ao-radius must be a finite number of metres > 0, or auto, got 'nan'");
    // Finite as a double, but a setting holds a float, where it would be
    // infinite.
    CHECK_THROWS_WITH(parse_setting_value(radius, "1e40"),
                      "--ao-radius must be a finite number of metres > 0, or auto, got '1e40' "
                      "(past the largest float, 3.4e38)");
    CHECK_THROWS_WITH(parse_setting_value(radius, "1e40x"),
                      "--ao-radius must be a finite number of metres > 0, or auto, got '1e40x'");
    CHECK(parse_setting_value(radius, "3e38") == 3e38f);
    CHECK_THROWS_WITH(check_setting(radius, 1e40),
                      "--ao-radius must be a finite number of metres > 0, or auto (past the "
                      "largest float, 3.4e38)");
}

// Oracle: the warehouse's box, 30 x 8 x 40 m, from make_warehouse.
TEST_CASE("scene scale: the radiosity radius stops at its fraction of a low interior's height",
          "[runtime][scale]") {
    const NumericSetting& row = *find_numeric_setting("radiosity-radius");
    REQUIRE(row.extent_fraction > 0.0f);
    const SceneScale warehouse = scene_scale(make_builtin_scene("warehouse"));
    CHECK(warehouse.smallest_extent == Approx(8.0f));
    CHECK(warehouse.bounding_radius ==
          Approx(0.5f * std::sqrt(30.0f * 30.0f + 8.0f * 8.0f + 40.0f * 40.0f)));
    CHECK(auto_length_value(row, warehouse) == Approx(row.extent_fraction * 8.0f));
    CHECK(auto_length_value(row, warehouse) < row.scene_fraction * warehouse.bounding_radius);
    // A flat scene (one quad) still gets a radius > 0: its extent counts as
    // 0.2 bounding radii.
    const SceneScale flat{.bounding_radius = 10.0f, .smallest_extent = 0.0f};
    CHECK(auto_length_value(row, flat) ==
          Approx(std::min(row.scene_fraction, 0.2f * row.extent_fraction) * 10.0f));
    // Rows without a cap are their fraction of the bounding radius alone.
    const NumericSetting& ao = *find_numeric_setting("ao-radius");
    CHECK(auto_length_value(ao, warehouse) ==
          Approx(ao.scene_fraction * warehouse.bounding_radius));
}

}  // namespace
}  // namespace deepgi
