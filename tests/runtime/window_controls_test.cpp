// The window's keys, settings table, script parser and fly-camera step,
// without a window.
#include "deepgi/errors.hpp"
#include "deepgi/window_controls.hpp"
#include "support/process.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <set>
#include <string>

using namespace deepgi;

namespace {

// The InputError message parse_script throws, or "" when it parses.
std::string script_error(const std::string& text) {
    try {
        parse_script(text, "s.txt");
    } catch (const InputError& error) {
        return error.what();
    }
    return {};
}

}  // namespace

TEST_CASE("window: a script parses into commands in file order", "[runtime][window]") {
    const auto commands = parse_script(
        "# comment line\n"
        "\n"
        "frame 0 set ao-radius 2.5   # trailing comment\n"
        "frame 0 set light-colour 1 0.5 0.25\n"
        "frame 3 key Shift+V\n"
        "frame 3 screenshot out/a\n"
        "frame 4 drop model.glb\n"
        "frame 9 quit",
        "s.txt");
    REQUIRE(commands.size() == 6);
    CHECK(commands[0].frame == 0);
    CHECK(commands[0].kind == ScriptCommand::Kind::set);
    CHECK(commands[0].name == "ao-radius");
    CHECK(commands[0].values == std::vector<std::string>{"2.5"});
    CHECK(commands[0].line == 3);
    CHECK(commands[1].values == std::vector<std::string>{"1", "0.5", "0.25"});
    CHECK(commands[2].kind == ScriptCommand::Kind::key);
    CHECK(commands[2].name == "Shift+V");
    CHECK(commands[3].kind == ScriptCommand::Kind::screenshot);
    CHECK(commands[3].values == std::vector<std::string>{"out/a"});
    CHECK(commands[4].kind == ScriptCommand::Kind::drop);
    CHECK(commands[5].kind == ScriptCommand::Kind::quit);
    CHECK(commands[5].frame == 9);
    CHECK(commands[5].line == 8);
}

TEST_CASE("window: script errors name the file, the line and the problem", "[runtime][window]") {
    CHECK(script_error("frame 1 quit\nquit\n") == "s.txt:2: expected 'frame N COMMAND ...'");
    CHECK(script_error("frame x quit") == "s.txt:1: frame 'x' is not a whole number >= 0");
    CHECK(script_error("frame -1 quit") == "s.txt:1: frame '-1' is not a whole number >= 0");
    CHECK(script_error("frame 5 quit\nframe 4 quit") ==
          "s.txt:2: frame 4 comes after frame 5; frames must not decrease");
    CHECK(script_error("frame 1 jump") ==
          "s.txt:1: unknown command 'jump' (set, key, hold, drag, resize, capture, "
          "screenshot, drop, quit)");
    CHECK(script_error("frame 1 set ao-radius -2") ==
          "s.txt:1: --ao-radius must be a finite number of metres > 0, or auto");
    CHECK(script_error("frame 1 set ao-radius big") ==
          "s.txt:1: ao-radius: 'big' is not a finite number");
    CHECK(script_error("frame 1 set ao-radius 1 2") ==
          "s.txt:1: set ao-radius takes 1 value(s), got 2");
    CHECK(script_error("frame 1 set ao-layers 1.5") ==
          "s.txt:1: ao-layers: '1.5' is not a whole number");
    CHECK(script_error("frame 1 set ao-layers 3") == "s.txt:1: --ao-layers must be 1 or 2, got 3");
    CHECK(script_error("frame 1 set radiosity-alpha 1") ==
          "s.txt:1: --radiosity-alpha must be a number in [0, 1)");
    CHECK(script_error("frame 1 set generator oracle") ==
          "s.txt:1: generator 'oracle' is not one of peel, previous, reproject, delay, predict");
    CHECK(script_error("frame 1 set radiosity-method mean") ==
          "s.txt:1: radiosity-method 'mean' is not one of area, published");
    CHECK(script_error("frame 1 set light-colour 1 -1 1") ==
          "s.txt:1: light-colour components must be >= 0");
    CHECK(script_error("frame 1 set light-intensity -3") ==
          "s.txt:1: light-intensity must be >= 0");
    CHECK(script_error("frame 1 set").find("s.txt:1: set needs a setting name and a value") == 0);
    CHECK(script_error("frame 1 set speed 3")
              .find("s.txt:1: unknown setting 'speed' (known: "
                    "min-separation, exposure,") == 0);
    CHECK(script_error("frame 1 key F13").find("s.txt:1: unknown key 'F13' (keys: V, Shift+V,") ==
          0);
    CHECK(script_error("frame 1 key") == "s.txt:1: key takes one key name");
    CHECK(script_error("frame 1 screenshot") == "s.txt:1: screenshot takes one path");
    CHECK(script_error("frame 1 drop a b") == "s.txt:1: drop takes one path");
    CHECK(script_error("frame 1 quit now") == "s.txt:1: quit takes no arguments");
    // The first bad line is reported, not a later one.
    CHECK(script_error("frame 1 quit\n\n# fine\nframe 2 nope\nframe 1 quit") ==
          "s.txt:4: unknown command 'nope' (set, key, hold, drag, resize, capture, "
          "screenshot, drop, quit)");
}

TEST_CASE("window: a bad --script stops deepgi before a window opens", "[runtime][window]") {
    const auto dir = spiral::test::make_scratch_dir("deepgi-script");
    const auto script = dir / "bad.txt";
    std::ofstream(script) << "frame 0 set exposure 0\n";
    const auto errors = dir / "stderr.txt";
    // No DISPLAY: reaching the window would fail with a different message.
    const int raw =
        std::system(fmt::format("env -u DISPLAY '{}' --size 64x36 --script '{}' 2> '{}'",
                                DEEPGI_EXECUTABLE, script.string(), errors.string())
                        .c_str());
    REQUIRE(WIFEXITED(raw));
    CHECK(WEXITSTATUS(raw) == 2);
    CHECK(spiral::test::read_file(errors) ==
          fmt::format("deepgi: error: {}:1: --exposure must be a finite number > 0, or auto\n",
                      script.string()));
    std::filesystem::remove_all(dir);
}

TEST_CASE("window: every table setting is a deepgi option, sliders stay valid",
          "[runtime][window]") {
    const auto dir = spiral::test::make_scratch_dir("deepgi-help");
    const auto help_file = dir / "help.txt";
    REQUIRE(std::system(
                fmt::format("'{}' --help > '{}'", DEEPGI_EXECUTABLE, help_file.string()).c_str()) ==
            0);
    const std::string help = spiral::test::read_file(help_file);
    std::set<std::string_view> names;
    for (const NumericSetting& setting : numeric_settings()) {
        INFO(setting.name);
        CHECK(names.insert(setting.name).second);
        CHECK(find_numeric_setting(setting.name) == &setting);
        // --help shows the option with its default (the table's getter of a
        // default RenderSettings).
        CHECK(help.find(fmt::format("--{} ", setting.name)) != std::string::npos);
        const RenderSettings defaults;
        for (float end : {setting.slider_min, setting.slider_max}) {
            RenderSettings settings;
            setting.set(settings, end);
            CHECK(setting.get(settings) == end);
            CHECK_NOTHROW(validate(settings));
        }
        CHECK(setting.get(defaults) >= setting.slider_min);
        CHECK(setting.get(defaults) <= setting.slider_max);
    }
    CHECK(find_numeric_setting("no-such") == nullptr);
    // The help lists every key of the table and says what leaving out --headless does.
    for (const KeyBinding& binding : key_bindings())
        CHECK(help.find(fmt::format("\n  {:<8} {}", binding.key, binding.description)) !=
              std::string::npos);
    CHECK(help.find("Without --headless it opens an interactive window") != std::string::npos);
    std::filesystem::remove_all(dir);
}

TEST_CASE("window: keys change the settings they name and keep them valid", "[runtime][window]") {
    std::set<std::string_view> keys;
    for (const KeyBinding& binding : key_bindings()) {
        CHECK(keys.insert(binding.key).second);
        CHECK(find_key_binding(binding.key) == &binding);
    }
    RenderSettings settings;
    KeyState state;
    REQUIRE(apply_key_action(KeyAction::ao_radius_up, settings, state));
    CHECK(settings.ao.radius == Approx(0.5f * 1.25f));
    apply_key_action(KeyAction::exposure_down, settings, state);
    CHECK(settings.exposure == Approx(1.0f / 1.25f));
    // Under auto, - and = take the exposure in use over as a manual value
    // and step from it; they never scale the auto marker.
    RenderSettings automatic;
    automatic.exposure = auto_length;
    KeyState measured;
    measured.exposure_in_use = 3.2f;
    REQUIRE(apply_key_action(KeyAction::exposure_down, automatic, measured));
    CHECK(automatic.exposure == Approx(3.2f / 1.25f));
    automatic.exposure = auto_length;
    REQUIRE(apply_key_action(KeyAction::exposure_up, automatic, measured));
    CHECK(automatic.exposure == Approx(3.2f * 1.25f));
    // Under auto, [ ] , . likewise step from the radius the last frame used.
    automatic.ao.radius = auto_length;
    automatic.radiosity.radius = auto_length;
    measured.in_use.ao.radius = 0.2f;
    measured.in_use.radiosity.radius = 3.0f;
    REQUIRE(apply_key_action(KeyAction::ao_radius_up, automatic, measured));
    CHECK(automatic.ao.radius == Approx(0.2f * 1.25f));
    REQUIRE(apply_key_action(KeyAction::radiosity_radius_down, automatic, measured));
    CHECK(automatic.radiosity.radius == Approx(3.0f / 1.25f));
    KeyLight unused_light;
    apply_set_command("exposure", {"auto"}, automatic, unused_light);
    CHECK(automatic.exposure == auto_length);
    CHECK_THROWS_AS(apply_set_command("guard-band", {"auto"}, automatic, unused_light), InputError);
    apply_key_action(KeyAction::next_generator, settings, state);
    CHECK(settings.generator == Generator::previous);
    apply_key_action(KeyAction::previous_view, settings, state);
    CHECK(settings.view == DebugView::reflection_hit_layer);  // wraps to the table's end
    apply_key_action(KeyAction::next_view, settings, state);
    CHECK(settings.view == DebugView::final_image);
    apply_key_action(KeyAction::toggle_layers, settings, state);
    CHECK(settings.ao.layers == 1);
    CHECK(settings.radiosity.layers == 1);
    apply_key_action(KeyAction::toggle_temporal, settings, state);
    CHECK(settings.radiosity.alpha == 0.0f);
    apply_key_action(KeyAction::toggle_temporal, settings, state);
    CHECK(settings.radiosity.alpha == RadiositySettings{}.alpha);
    // The window's own actions leave the settings alone.
    const RenderSettings before = settings;
    CHECK_FALSE(apply_key_action(KeyAction::screenshot, settings, state));
    CHECK(settings.exposure == before.exposure);
    // A key never makes the settings invalid: radius steps stop short of 0.
    for (int i = 0; i < 2000; ++i) apply_key_action(KeyAction::ao_radius_down, settings, state);
    CHECK(settings.ao.radius > 0.0f);
    CHECK_NOTHROW(validate(settings));
}

TEST_CASE("window: at 5 fps a held key moves no further per step than at 20 fps",
          "[runtime][window]") {
    const float speed = 2.0f;  // m/s
    // 60 fps: the step is speed * frame time, so a second of frames covers 2 m.
    float sixty = 0.0f;
    for (int i = 0; i < 60; ++i) sixty += fly_step(1.0f / 60.0f, speed);
    CHECK(sixty == Approx(2.0f).epsilon(1e-5));
    // 5 fps: each 200 ms step is capped at 50 ms, 10 cm here, so a wall
    // thicker than 10 cm cannot be skipped in one step.
    CHECK(fly_step(0.2f, speed) == Approx(0.1f));
    CHECK(fly_step(3.0f, speed) == Approx(0.1f));  // a stall is no jump either
    CHECK(fly_step(0.0f, speed) == 0.0f);
    CHECK(fly_step(-1.0f, speed) == 0.0f);
    CHECK(fly_step(std::nanf(""), speed) == 0.0f);
}

TEST_CASE("window: set commands edit the light", "[runtime][window]") {
    RenderSettings settings;
    KeyLight light;
    light.kind = LightKind::directional;
    // Pitch first: the default light points straight down, where yaw is
    // undefined (a set of yaw there would be lost to the pole).
    apply_set_command("light-pitch", {"30"}, settings, light);
    apply_set_command("light-yaw", {"90"}, settings, light);
    // Yaw 90 degrees about +Y from -Z is +X; pitch 30 degrees below the horizon.
    CHECK(light.direction.x == Approx(std::cos(glm::radians(30.0f))));
    CHECK(light.direction.y == Approx(-0.5f));
    CHECK(light.direction.z == Approx(0.0f).margin(1e-6));
    apply_set_command("light-intensity", {"7.5"}, settings, light);
    CHECK(light.intensity == 7.5f);
    CHECK_THROWS_WITH(apply_set_command("light-position", {"0", "1", "0"}, settings, light),
                      "light-position: the key light is directional (it has no position)");
    light.kind = LightKind::spot;
    apply_set_command("light-position", {"0", "1", "-2"}, settings, light);
    CHECK(light.position == glm::vec3(0.0f, 1.0f, -2.0f));
    apply_set_command("view", {"ao-raw"}, settings, light);
    CHECK(settings.view == DebugView::ao_raw);
    const LightAngles angles = light_angles(light_direction({0.4f, 0.7f}));
    CHECK(angles.yaw == Approx(0.4f));
    CHECK(angles.pitch == Approx(0.7f));
}

namespace {

// A value on the refused side of a limit, and one on the accepted side.
float just_outside(const NumericSetting& row, float limit, bool inclusive, float direction) {
    if (!inclusive) return limit;
    const float step = row.integer ? 1.0f : std::max(1e-3f, std::abs(limit) * 1e-3f);
    return limit + direction * step;
}
float just_inside(const NumericSetting& row, float limit, bool inclusive, float direction) {
    if (inclusive) return limit;
    return row.integer ? limit - direction : std::nextafter(limit, -direction * INFINITY);
}

}  // namespace

TEST_CASE(
    "settings: every row has help and an owner, its default inside its limits, and the "
    "command line refuses a value just outside each limit",
    "[runtime][settings]") {
    const RenderSettings defaults;
    for (const NumericSetting& row : numeric_settings()) {
        INFO(row.name);
        CHECK_FALSE(row.help.empty());
        // That the owner is a pass of the list: settings_owner_test.cpp.
        CHECK_FALSE(row.owner.empty());
        CHECK_NOTHROW(check_setting(row, row.get(defaults)));
        struct Limit {
            float value;
            bool inclusive;
            float direction;  // towards the refused side
        };
        std::vector<Limit> limits = {{row.minimum, row.minimum_inclusive, -1.0f}};
        if (std::isfinite(row.maximum))
            limits.push_back({row.maximum, row.maximum_inclusive, 1.0f});
        for (const Limit& limit : limits) {
            const float inside = just_inside(row, limit.value, limit.inclusive, limit.direction);
            const float outside = just_outside(row, limit.value, limit.inclusive, limit.direction);
            INFO("inside " << inside << ", outside " << outside);
            RenderSettings settings;
            row.set(settings, inside);
            CHECK_NOTHROW(validate(settings));
            CHECK_THROWS_WITH(check_setting(row, outside),
                              Catch::StartsWith(fmt::format("--{} must be ", row.name)));
            // The command line refuses it before any rendering, with one line
            // naming the option, exit status 2.
            const auto result = spiral::test::run_command(
                fmt::format("'{}' --headless --size 8x8 --output /nonexistent/x.png --{}={}",
                            DEEPGI_EXECUTABLE, row.name, fmt::format("{:.9g}", outside)));
            CHECK(result.status == 2);
            CHECK(result.err.rfind(fmt::format("deepgi: error: --{} must be ", row.name), 0) == 0);
            CHECK(spiral::test::count_lines(result.err) == 1);
        }
    }
}

TEST_CASE("window: hold, drag, resize and capture parse, and their errors name the line",
          "[runtime][window]") {
    const auto commands = parse_script(
        "frame 1 hold W 3\n"
        "frame 1 drag 40 -15.5\n"
        "frame 2 resize 320 180\n"
        "frame 3 capture out/w.PNG\n",
        "s.txt");
    REQUIRE(commands.size() == 4);
    CHECK(commands[0].kind == ScriptCommand::Kind::hold);
    CHECK(commands[0].name == "W");
    CHECK(commands[0].numbers[0] == 3.0);
    CHECK(commands[1].kind == ScriptCommand::Kind::drag);
    CHECK(commands[1].numbers[0] == 40.0);
    CHECK(commands[1].numbers[1] == -15.5);
    CHECK(commands[2].kind == ScriptCommand::Kind::resize);
    CHECK(commands[2].numbers[0] == 320.0);
    CHECK(commands[2].numbers[1] == 180.0);
    CHECK(commands[3].kind == ScriptCommand::Kind::capture);
    CHECK(commands[3].values == std::vector<std::string>{"out/w.PNG"});

    CHECK(script_error("frame 1 hold G 3") ==
          "s.txt:1: hold: 'G' is not a movement key (W, A, S, D, Q, E)");
    CHECK(script_error("frame 1 hold W 0") ==
          "s.txt:1: hold: frames '0' is not a whole number from 1 to 100000");
    CHECK(script_error("frame 1 hold W") == "s.txt:1: hold takes a key and a number of frames");
    CHECK(script_error("frame 1 drag 1 nan") == "s.txt:1: drag: 'nan' is not a finite number");
    CHECK(script_error("frame 1 drag 1") == "s.txt:1: drag takes DX DY in pixels");
    CHECK(script_error("frame 1 resize 0 10") ==
          "s.txt:1: resize: width '0' is not a whole number from 1 to 16384");
    CHECK(script_error("frame 1 resize 10 2.5") ==
          "s.txt:1: resize: height '2.5' is not a whole number from 1 to 16384");
    CHECK(script_error("frame 1 capture out/w.jpg") ==
          "s.txt:1: capture: the path must end in .png");
}

TEST_CASE("window: a drag turns the camera 0.004 rad a pixel, a held key moves one step",
          "[runtime][window]") {
    Camera camera;
    camera.yaw = 0.25f;
    camera.pitch = 0.1f;
    mouse_look(camera, 100.0f, 50.0f);  // right and down
    CHECK(camera.yaw == Approx(0.25 + 0.4).margin(1e-6));
    CHECK(camera.pitch == Approx(0.1 - 0.2).margin(1e-6));
    mouse_look(camera, 0.0f, -10000.0f);  // far up: held at the limit
    CHECK(camera.pitch == max_look_pitch);

    Camera level;  // yaw 0 looks down -Z
    MoveKeys keys;
    *move_key_flag(keys, "W") = true;
    fly_move(level, keys, 0.5f);
    CHECK(level.position.z == Approx(-0.5f));
    CHECK(level.position.x == Approx(0.0f).margin(1e-7));
    MoveKeys right_up;
    *move_key_flag(right_up, "D") = true;
    *move_key_flag(right_up, "E") = true;
    const glm::vec3 before = level.position;
    fly_move(level, right_up, 1.0f);  // +X and +Y together, one step long
    CHECK(level.position.x - before.x == Approx(std::sqrt(0.5f)));
    CHECK(level.position.y - before.y == Approx(std::sqrt(0.5f)));
    CHECK(move_key_flag(keys, "G") == nullptr);
    fly_move(level, MoveKeys{}, 1.0f);
    CHECK(level.position.x - before.x == Approx(std::sqrt(0.5f)));
}

TEST_CASE("camera: a pose parses, refuses bad values and round-trips bit for bit",
          "[runtime][window]") {
    const Camera camera = parse_camera_pose("pose:1,2.5,-3,90,-30,60,0.05");
    CHECK(camera.position == glm::vec3(1.0f, 2.5f, -3.0f));
    CHECK(camera.yaw == Approx(std::acos(-1.0) / 2.0));
    CHECK(camera.pitch == Approx(-std::acos(-1.0) / 6.0));
    CHECK(camera.vertical_fov == Approx(std::acos(-1.0) / 3.0));
    CHECK(camera.near_plane == 0.05f);

    auto error = [](const std::string& text) {
        try {
            parse_camera_pose(text);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(error("pose:1,2,3,0,0,60") ==
          "--camera 'pose:1,2,3,0,0,60': expected 7 values: pose:X,Y,Z,YAW,PITCH,FOVY,NEAR "
          "(degrees, scene units)");
    CHECK(error("pose:1,2,3,0,0,60,0.1,4") ==
          "--camera 'pose:1,2,3,0,0,60,0.1,4': expected 7 values: pose:X,Y,Z,YAW,PITCH,FOVY,NEAR "
          "(degrees, scene units)");
    CHECK(error("pose:1,x,3,0,0,60,0.1") ==
          "--camera 'pose:1,x,3,0,0,60,0.1': value 2 'x' is not a finite number "
          "(pose:X,Y,Z,YAW,PITCH,FOVY,NEAR)");
    CHECK(error("pose:1,inf,3,0,0,60,0.1").find("value 2 'inf' is not a finite number") !=
          std::string::npos);
    CHECK(error("pose:0,0,0,0,90,60,0.1").find("PITCH must be between -90 and 90") !=
          std::string::npos);
    CHECK(error("pose:0,0,0,0,0,180,0.1").find("FOVY must be between 0 and 180") !=
          std::string::npos);
    CHECK(error("pose:0,0,0,0,0,60,0").find("NEAR must be > 0") != std::string::npos);

    // Angles a mouse left anywhere, written in degrees, come back the same floats.
    for (float yaw : {0.0f, 0.1f + 40 * 0.004f, -7.3f, 123.456f}) {
        Camera original;
        original.position = glm::vec3(0.0513866693f, 1.0f / 3.0f, -1234.5678f);
        original.yaw = yaw;
        original.pitch = -1.5f + 0.004f * 7;
        original.vertical_fov = 0.7f;
        original.near_plane = 0.0123f;
        const Camera back = parse_camera_pose(format_camera_pose(original));
        INFO(format_camera_pose(original));
        CHECK(back.position == original.position);
        CHECK(back.yaw == original.yaw);
        CHECK(back.pitch == original.pitch);
        CHECK(back.vertical_fov == original.vertical_fov);
        CHECK(back.near_plane == original.near_plane);
    }
}
