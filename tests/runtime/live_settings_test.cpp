// The renderer's in-place edits the window relies on: the key light and the
// settings change without a rebuild, and match a renderer built fresh with
// the edited values.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/renderer.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using namespace deepgi;

namespace {

RenderSettings small_settings() {
    RenderSettings settings;
    settings.width = 96;
    settings.height = 54;
    settings.shadow_map_size = 256;
    return settings;
}

}  // namespace

TEST_CASE("live settings: an edited key light renders as a renderer built with it",
          "[runtime][window]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const Scene scene = make_builtin_scene("atrium");
    KeyLight turned = scene.key_light;
    turned.direction = glm::normalize(glm::vec3(-0.6f, -0.5f, 0.3f));
    turned.colour = {1.0f, 0.5f, 0.25f};
    turned.intensity = 2.0f * scene.key_light.intensity;

    Renderer live(scene, small_settings(), loader);
    live.render(scene.default_camera);
    live.set_key_light(turned);
    live.render(scene.default_camera);

    Scene edited = scene;
    edited.key_light = turned;
    Renderer fresh(edited, small_settings(), loader);
    fresh.render(scene.default_camera);
    // Direct light and the shadow map depend only on this frame: bit for bit.
    for (const char* name :
         {"shadow-depth", "direct_light-radiance-layer0", "direct_light-radiance-layer1"}) {
        INFO(name);
        CHECK(live.read_pass_output(name).pixels == fresh.read_pass_output(name).pixels);
    }
    CHECK(live.key_light().intensity == turned.intensity);
    // The temporal filter keeps its history: the light fades in, it is no cut.
    CHECK(live.history_valid());
}

TEST_CASE("live settings: doubling the light intensity doubles the direct light",
          "[runtime][window]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    Renderer renderer(scene, small_settings(), ShaderLoader::from_build_configuration());
    renderer.render(scene.default_camera);
    const FloatImage once = renderer.read_pass_output("direct_light-radiance-layer0");
    KeyLight light = renderer.key_light();
    light.intensity *= 2.0f;
    renderer.set_key_light(light);
    renderer.render(scene.default_camera);
    const FloatImage twice = renderer.read_pass_output("direct_light-radiance-layer0");
    // Radiance is linear in the intensity, and doubling is exact in floats
    // (also after RGBA16F rounding).
    int lit = 0;
    for (std::size_t i = 0; i < once.pixels.size(); ++i) {
        CHECK(twice.pixels[i] == 2.0f * once.pixels[i]);
        if (once.pixels[i] > 0.0f) ++lit;
    }
    CHECK(lit > 100);
}

TEST_CASE("live settings: bad light values are refused and the light is kept",
          "[runtime][window]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    Renderer renderer(scene, small_settings(), ShaderLoader::from_build_configuration());
    KeyLight light = scene.key_light;
    light.direction = glm::vec3(0.0f);
    CHECK_THROWS_WITH(renderer.set_key_light(light), "light: the direction must not be zero");
    light = scene.key_light;
    light.intensity = -1.0f;
    CHECK_THROWS_WITH(renderer.set_key_light(light), "light: intensity and colour must be >= 0");
    light = scene.key_light;
    light.colour.g = std::nanf("");
    CHECK_THROWS_WITH(renderer.set_key_light(light), "light: every value must be finite");
    CHECK(renderer.key_light().intensity == scene.key_light.intensity);
    CHECK(renderer.key_light().direction == scene.key_light.direction);
}

TEST_CASE("live settings: only a change of the radiosity layers or method drops history",
          "[runtime][window]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    Renderer renderer(scene, small_settings(), ShaderLoader::from_build_configuration());
    renderer.render(scene.default_camera);
    REQUIRE(renderer.history_valid());
    RenderSettings settings = renderer.settings();
    settings.ao.radius = 2.0f;
    settings.radiosity.radius = 0.5f;
    settings.radiosity.alpha = 0.5f;
    settings.exposure = 2.0f;
    settings.generator = Generator::reproject;
    renderer.set_settings(settings);
    CHECK(renderer.history_valid());
    settings.radiosity.layers = 1;
    renderer.set_settings(settings);
    CHECK_FALSE(renderer.history_valid());
    CHECK(renderer.history_log().back().find("radiosity layers changed to 1") != std::string::npos);
    renderer.render(scene.default_camera);
    REQUIRE(renderer.history_valid());
    settings.radiosity.method = RadiosityMethod::published;
    renderer.set_settings(settings);
    CHECK_FALSE(renderer.history_valid());
    CHECK(renderer.history_log().back().find("radiosity method changed to published") !=
          std::string::npos);
}

TEST_CASE("live settings: an edited blur filters as a renderer built with it",
          "[runtime][window]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const Scene scene = make_builtin_scene("cornell");
    RenderSettings base = small_settings();
    base.ao.alpha = 0.0f;  // the blur's AO input is then this frame's SAO alone
    RenderSettings sharp = base;
    sharp.blur.depth_tolerance = 0.01f;
    sharp.blur.normal_power = 32.0f;
    sharp.blur.plane_tolerance = 0.002f;
    sharp.blur.extent = 0.1f;

    Renderer live(scene, base, loader);
    live.render(scene.default_camera);
    live.set_settings(sharp);
    live.render(scene.default_camera);

    Renderer fresh(scene, sharp, loader);
    Renderer unchanged(scene, base, loader);
    for (int frame = 0; frame < 2; ++frame) {
        fresh.render(scene.default_camera);
        unchanged.render(scene.default_camera);
    }
    // Same inputs on the second frame (the blur feeds no history), so the
    // blurred outputs agree bit for bit, and differ from the default blur's.
    for (const char* name : {"ao-blurred", "radiosity-blurred"}) {
        INFO(name);
        CHECK(live.read_pass_output(name).pixels == fresh.read_pass_output(name).pixels);
        CHECK(live.read_pass_output(name).pixels != unchanged.read_pass_output(name).pixels);
    }
    CHECK(live.history_valid());
}

TEST_CASE("live settings: bad blur values are refused with the option's name",
          "[runtime][window]") {
    RenderSettings settings = small_settings();
    settings.blur.normal_power = 0.0f;
    CHECK_THROWS_WITH(validate(settings), "--blur-normal-power must be a finite number > 0");
    settings = small_settings();
    settings.blur.depth_tolerance = std::nanf("");
    CHECK_THROWS_WITH(validate(settings), "--blur-depth-tolerance must be a finite number > 0");
    settings = small_settings();
    settings.blur.plane_tolerance = -1.0f;
    CHECK_THROWS_WITH(validate(settings), "--blur-plane-tolerance must be a finite number > 0");
    settings = small_settings();
    settings.blur.extent = -0.5f;
    CHECK_THROWS_WITH(validate(settings), "--blur-extent must be a finite number >= 0");
    settings.blur.extent = std::numeric_limits<float>::infinity();
    CHECK_THROWS_WITH(validate(settings), "--blur-extent must be a finite number >= 0");
}
