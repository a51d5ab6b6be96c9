// The renderer's in-place edits the window relies on: the key light and the
// settings change without a rebuild, and match a renderer built fresh with
// the edited values.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/renderer.hpp"

#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

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
    // (also after R11F_G11F_B10F rounding).
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

namespace {

// A value of `row` other than the one `settings` holds that the row's limits
// accept: an end of its slider, or the slider's middle.
float changed_value(const NumericSetting& row, const RenderSettings& settings) {
    const float current = row.get(settings);
    for (float value : {row.slider_max, row.slider_min, 0.5f * (row.slider_min + row.slider_max)}) {
        if (row.integer) value = std::round(value);
        if (value == current) continue;
        try {
            check_setting(row, value);
        } catch (const InputError&) {
            continue;
        }
        return value;
    }
    FAIL("no other valid value for --" << row.name);
    return current;
}

}  // namespace

TEST_CASE(
    "live settings: the rows marked drop_history, the radiosity method and a generator "
    "with another layer count drop history, and the rows marked none keep it",
    "[runtime][window]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    Renderer renderer(scene, small_settings(), ShaderLoader::from_build_configuration());
    renderer.render(scene.default_camera);
    REQUIRE(renderer.history_valid());

    // Edits that are read every frame keep history: every row the table
    // marks SettingEffect::none, one at a time, and a generator with the
    // same layer count.
    int kept = 0;
    for (const NumericSetting& row : numeric_settings()) {
        if (row.effect != SettingEffect::none) continue;
        RenderSettings settings = renderer.settings();
        row.set(settings, changed_value(row, settings));
        renderer.set_settings(settings);
        INFO("--" << row.name << " " << row.get(settings));
        CHECK(renderer.history_valid());
        ++kept;
    }
    CHECK(kept > 20);
    {
        RenderSettings settings = renderer.settings();
        settings.generator = Generator::reproject;  // two layers, as peel
        renderer.set_settings(settings);
        CHECK(renderer.history_valid());
    }

    // Every row the table marks SettingEffect::drop_history drops it, and
    // the log names the row. The oracle for which rows those must be: the
    // radiosity history holds a sum over the gathered layers and over the
    // samples the visibility test lets through, so a change of either would
    // take cycles to fade (docs/radiosity.md).
    std::vector<std::string> dropping;
    for (const NumericSetting& row : numeric_settings()) {
        if (row.effect != SettingEffect::drop_history) continue;
        RenderSettings settings = renderer.settings();
        const float value = changed_value(row, settings);
        row.set(settings, value);
        renderer.set_settings(settings);
        INFO("--" << row.name << " " << value);
        CHECK_FALSE(renderer.history_valid());
        CHECK(renderer.history_log().back() ==
              fmt::format("history invalidated: {} {} changed to {}", row.group, row.label, value));
        dropping.emplace_back(row.name);
        renderer.render(scene.default_camera);
        REQUIRE(renderer.history_valid());
    }
    CHECK(dropping == std::vector<std::string>{"radiosity-layers", "radiosity-visibility-steps"});
    // (The rows marked reallocate are not here: the guard band resizes the
    // frame, which drops history, as the resize tests of
    // pass_interface_test.cpp check.)

    // What no row covers, the passes say themselves: the radiosity method
    // (its estimators' E mean different things) and a generator with a third
    // layer (the depth history changes meaning).
    RenderSettings settings = renderer.settings();
    settings.radiosity.method = RadiosityMethod::published;
    renderer.set_settings(settings);
    CHECK_FALSE(renderer.history_valid());
    CHECK(renderer.history_log().back() ==
          "history invalidated: radiosity method changed to published");
    renderer.render(scene.default_camera);
    REQUIRE(renderer.history_valid());
    settings.generator = Generator::delay;
    renderer.set_settings(settings);
    CHECK_FALSE(renderer.history_valid());
    CHECK(renderer.history_log().back() ==
          "history invalidated: generator reproject -> delay (the layer 1 "
          "reference changes)");
}

TEST_CASE("live settings: a reallocation that keeps the frame's size keeps the running mean",
          "[runtime][window]") {
    // A new shadow map size re-creates every pass's targets. The AO does not
    // depend on the shadow, so a still camera's running mean must go on as
    // in a renderer that never changed it: bit for bit. (When the history
    // textures were re-created with the rest, they came back cleared while
    // history still counted as valid.)
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    Renderer edited(scene, small_settings(), ShaderLoader::from_build_configuration());
    Renderer untouched(scene, small_settings(), ShaderLoader::from_build_configuration());
    for (int frame = 0; frame < 4; ++frame) {
        edited.render(scene.default_camera);
        untouched.render(scene.default_camera);
    }
    const std::size_t log_length = edited.history_log().size();
    RenderSettings settings = edited.settings();
    settings.shadow_map_size = 512;
    edited.set_settings(settings);
    CHECK(edited.history_valid());
    CHECK(edited.history_log().size() == log_length);
    edited.render(scene.default_camera);
    untouched.render(scene.default_camera);
    const FloatImage a = edited.read_pass_output("ao-temporal");
    const FloatImage b = untouched.read_pass_output("ao-temporal");
    REQUIRE(a.pixels.size() == b.pixels.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) differing += a.pixels[i] != b.pixels[i];
    CHECK(differing == 0);

    // The pyramid's depth reallocates too and keeps history the same way.
    settings = edited.settings();
    settings.depth_pyramid.max_mip_level -= 1;
    edited.set_settings(settings);
    CHECK(edited.history_valid());
    CHECK(edited.history_log().size() == log_length);
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
