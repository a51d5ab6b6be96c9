// Keys, script commands and fly-camera steps of the interactive window.
#include "deepgi/window_controls.hpp"

#include "deepgi/errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace deepgi {

namespace {

constexpr std::array<KeyBinding, 17> key_table = {{
    {"V", KeyAction::next_view, "next debug view"},
    {"Shift+V", KeyAction::previous_view, "previous debug view"},
    {"G", KeyAction::next_generator, "next deep G-buffer generator"},
    {"M", KeyAction::next_ao_method, "next AO estimator"},
    {"[", KeyAction::ao_radius_down, "AO radius / 1.25 (from auto: the value in use)"},
    {"]", KeyAction::ao_radius_up, "AO radius * 1.25 (from auto: the value in use)"},
    {",", KeyAction::radiosity_radius_down,
     "radiosity radius / 1.25 (from auto: the value in use)"},
    {".", KeyAction::radiosity_radius_up, "radiosity radius * 1.25 (from auto: the value in use)"},
    {"-", KeyAction::exposure_down, "exposure / 1.25 (from auto: the value in use)"},
    {"=", KeyAction::exposure_up, "exposure * 1.25 (from auto: the value in use)"},
    {"L", KeyAction::toggle_layers, "AO and radiosity layers 2 <-> 1"},
    {"T", KeyAction::toggle_temporal, "radiosity temporal filter off <-> on"},
    {"R", KeyAction::reset_camera, "reset the camera"},
    {"Home", KeyAction::reset_camera, "reset the camera"},
    {"F12", KeyAction::screenshot, "screenshot: PNG + pass PFMs in a dated folder"},
    {"F1", KeyAction::toggle_panel, "hide / show the panel"},
    {"Escape", KeyAction::quit, "quit"},
}};

template <class Enum>
Enum step_enum(Enum value, int steps) {
    const auto table = enum_names(Enum{});
    const int count = int(table.size());
    int current = 0;
    for (int i = 0; i < count; ++i)
        if (table[std::size_t(i)].value == value) current = i;
    return table[std::size_t(((current + steps) % count + count) % count)].value;
}

// Scales a float setting and keeps it inside validate()'s range by refusing
// a step that would leave it (the key then does nothing). A length on `auto`
// has no number to scale: the step starts from the length the last frame
// used (`in_use`), which then stays as a manual value.
void scale_setting(RenderSettings& settings, std::string_view name, float factor,
                   const RenderSettings& in_use) {
    const NumericSetting* setting = find_numeric_setting(name);
    RenderSettings trial = settings;
    float value = setting->get(settings);
    if (value == auto_length) value = setting->get(in_use);
    if (!(value > 0.0f)) return;  // nothing resolved yet
    setting->set(trial, value * factor);
    try {
        validate(trial);
        settings = trial;
    } catch (const InputError&) {
    }
}

std::vector<std::string> split_words(std::string_view line) {
    std::vector<std::string> words;
    std::istringstream stream{std::string(line)};
    std::string word;
    while (stream >> word) words.push_back(word);
    return words;
}

float parse_float(const std::string& name, const std::string& text) {
    float value = 0.0f;
    const char* end = text.data() + text.size();
    const auto result = std::from_chars(text.data(), end, value);
    if (result.ec != std::errc() || result.ptr != end || !std::isfinite(value))
        throw InputError(fmt::format("{}: '{}' is not a finite number", name, text));
    return value;
}

std::size_t expected_values(std::string_view name) {
    if (name == "light-colour" || name == "light-position") return 3;
    return 1;
}

bool is_light_setting(std::string_view name) {
    return name == "light-intensity" || name == "light-colour" || name == "light-yaw" ||
           name == "light-pitch" || name == "light-position";
}

bool is_known_setting(std::string_view name) {
    return find_numeric_setting(name) != nullptr || name == "generator" || name == "view" ||
           name == "ao-method" || name == "radiosity-method" || is_light_setting(name);
}

// A whole number in [low, high] for a script argument; `fail` throws.
template <class Fail>
int whole_number(const std::string& text, int low, int high, std::string_view what, Fail fail) {
    int value = 0;
    const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
    if (result.ec != std::errc() || result.ptr != text.data() + text.size() || value < low ||
        value > high)
        fail(fmt::format("{} '{}' is not a whole number from {} to {}", what, text, low, high));
    return value;
}

}  // namespace

std::span<const KeyBinding> key_bindings() {
    return key_table;
}

const KeyBinding* find_key_binding(std::string_view key) {
    for (const auto& binding : key_table)
        if (binding.key == key) return &binding;
    return nullptr;
}

std::string_view movement_help() {
    return "W/A/S/D move, Q/E down/up (held; speed scales with frame time, capped at 50 ms a "
           "step), right mouse drag looks, scroll wheel changes the fly speed";
}

std::string key_help_text() {
    std::string text;
    for (const auto& binding : key_table)
        text += fmt::format("  {:<8} {}\n", binding.key, binding.description);
    return text;
}

bool apply_key_action(KeyAction action, RenderSettings& settings, KeyState& state) {
    switch (action) {
        case KeyAction::next_view:
            settings.view = step_enum(settings.view, 1);
            return true;
        case KeyAction::previous_view:
            settings.view = step_enum(settings.view, -1);
            return true;
        case KeyAction::next_generator:
            settings.generator = step_enum(settings.generator, 1);
            return true;
        case KeyAction::next_ao_method:
            settings.ao.method = step_enum(settings.ao.method, 1);
            return true;
        case KeyAction::ao_radius_down:
            scale_setting(settings, "ao-radius", 1.0f / 1.25f, state.in_use);
            return true;
        case KeyAction::ao_radius_up:
            scale_setting(settings, "ao-radius", 1.25f, state.in_use);
            return true;
        case KeyAction::radiosity_radius_down:
            scale_setting(settings, "radiosity-radius", 1.0f / 1.25f, state.in_use);
            return true;
        case KeyAction::radiosity_radius_up:
            scale_setting(settings, "radiosity-radius", 1.25f, state.in_use);
            return true;
        case KeyAction::exposure_down:
        case KeyAction::exposure_up:
            // Scaling the auto marker would mean nothing: the key takes the
            // measured value over as a manual one and steps from there.
            if (settings.exposure == auto_length && state.exposure_in_use > 0.0f)
                settings.exposure = state.exposure_in_use;
            scale_setting(settings, "exposure",
                          action == KeyAction::exposure_up ? 1.25f : 1.0f / 1.25f, settings);
            return true;
        case KeyAction::toggle_layers: {
            const int layers = settings.ao.layers == 1 ? limits::max_ao_layers : 1;
            settings.ao.layers = layers;
            settings.radiosity.layers = std::min(layers, limits::max_radiosity_layers);
            return true;
        }
        case KeyAction::toggle_temporal:
            if (settings.radiosity.alpha > 0.0f) {
                state.remembered_alpha = settings.radiosity.alpha;
                settings.radiosity.alpha = 0.0f;
            } else {
                settings.radiosity.alpha = state.remembered_alpha;
            }
            return true;
        case KeyAction::reset_camera:
        case KeyAction::screenshot:
        case KeyAction::toggle_panel:
        case KeyAction::quit:
            return false;
    }
    return false;
}

float fly_step(float frame_seconds, float metres_per_second) {
    if (!(frame_seconds > 0.0f)) return 0.0f;  // also NaN: a clock glitch moves nothing
    return metres_per_second * std::min(frame_seconds, max_fly_step_seconds);
}

void mouse_look(Camera& camera, float dx, float dy) {
    camera.yaw += dx * look_radians_per_pixel;
    camera.pitch =
        std::clamp(camera.pitch - dy * look_radians_per_pixel, -max_look_pitch, max_look_pitch);
}

bool* move_key_flag(MoveKeys& keys, std::string_view key) {
    if (key == "W") return &keys.forward;
    if (key == "S") return &keys.back;
    if (key == "A") return &keys.left;
    if (key == "D") return &keys.right;
    if (key == "Q") return &keys.down;
    if (key == "E") return &keys.up;
    return nullptr;
}

void fly_move(Camera& camera, const MoveKeys& keys, float step) {
    const glm::vec3 forward = camera_forward(camera);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    glm::vec3 move(0.0f);
    if (keys.forward) move += forward;
    if (keys.back) move -= forward;
    if (keys.right) move += right;
    if (keys.left) move -= right;
    if (keys.up) move.y += 1.0f;
    if (keys.down) move.y -= 1.0f;
    if (glm::length(move) > 0.0f) camera.position += glm::normalize(move) * step;
}

LightAngles light_angles(glm::vec3 direction) {
    const glm::vec3 d = glm::normalize(direction);
    return {std::atan2(d.x, -d.z), std::asin(std::clamp(-d.y, -1.0f, 1.0f))};
}

glm::vec3 light_direction(LightAngles angles) {
    return {std::cos(angles.pitch) * std::sin(angles.yaw), -std::sin(angles.pitch),
            -std::cos(angles.pitch) * std::cos(angles.yaw)};
}

void apply_set_command(const std::string& name, const std::vector<std::string>& values,
                       RenderSettings& settings, KeyLight& light) {
    if (values.size() != expected_values(name)) {
        throw InputError(fmt::format("set {} takes {} value(s), got {}", name,
                                     expected_values(name), values.size()));
    }
    if (const NumericSetting* setting = find_numeric_setting(name)) {
        // `auto` for a length or the exposure; a number is checked as
        // typed, so -1 is never taken for auto_length.
        const float value = accepts_auto(*setting) && values[0] == "auto"
                                ? auto_length
                                : parse_float(name, values[0]);
        if (setting->integer && value != std::round(value))
            throw InputError(fmt::format("{}: '{}' is not a whole number", name, values[0]));
        if (values[0] != "auto") check_setting(*setting, value);
        RenderSettings trial = settings;
        setting->set(trial, value);
        validate(trial);
        settings = trial;
    } else if (name == "generator") {
        settings.generator = parse_generator("generator", values[0]);
    } else if (name == "view") {
        settings.view = parse_debug_view("view", values[0]);
    } else if (name == "ao-method") {
        settings.ao.method = parse_ao_method("ao-method", values[0]);
    } else if (name == "radiosity-method") {
        settings.radiosity.method = parse_radiosity_method("radiosity-method", values[0]);
    } else if (name == "light-intensity") {
        const float value = parse_float(name, values[0]);
        if (value < 0.0f) throw InputError("light-intensity must be >= 0");
        light.intensity = value;
    } else if (name == "light-colour") {
        glm::vec3 colour;
        for (int i = 0; i < 3; ++i) colour[i] = parse_float(name, values[std::size_t(i)]);
        if (glm::any(glm::lessThan(colour, glm::vec3(0.0f))))
            throw InputError("light-colour components must be >= 0");
        light.colour = colour;
    } else if (name == "light-yaw" || name == "light-pitch") {
        LightAngles angles = light_angles(light.direction);
        const float radians = glm::radians(parse_float(name, values[0]));
        (name == "light-yaw" ? angles.yaw : angles.pitch) = radians;
        light.direction = light_direction(angles);
    } else if (name == "light-position") {
        if (light.kind == LightKind::directional)
            throw InputError("light-position: the key light is directional (it has no position)");
        for (int i = 0; i < 3; ++i) light.position[i] = parse_float(name, values[std::size_t(i)]);
    } else {
        throw InputError(fmt::format("unknown setting '{}'", name));
    }
}

std::vector<ScriptCommand> parse_script(std::string_view text, std::string_view source) {
    std::vector<ScriptCommand> commands;
    int line_number = 0;
    int last_frame = 0;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        std::string_view line = text.substr(start, end - start);
        start = end + 1;
        ++line_number;
        if (const auto hash = line.find('#'); hash != std::string_view::npos)
            line = line.substr(0, hash);
        const std::vector<std::string> words = split_words(line);
        if (words.empty()) continue;
        auto fail = [&](const std::string& problem) {
            throw InputError(fmt::format("{}:{}: {}", source, line_number, problem));
        };
        if (words[0] != "frame" || words.size() < 3) fail("expected 'frame N COMMAND ...'");
        ScriptCommand command;
        command.line = line_number;
        {
            const std::string& number = words[1];
            const auto result =
                std::from_chars(number.data(), number.data() + number.size(), command.frame);
            if (result.ec != std::errc() || result.ptr != number.data() + number.size() ||
                command.frame < 0) {
                fail(fmt::format("frame '{}' is not a whole number >= 0", number));
            }
        }
        if (command.frame < last_frame)
            fail(fmt::format("frame {} comes after frame {}; frames must not decrease",
                             command.frame, last_frame));
        last_frame = command.frame;
        const std::string& verb = words[2];
        const std::vector<std::string> arguments(words.begin() + 3, words.end());
        if (verb == "set") {
            command.kind = ScriptCommand::Kind::set;
            if (arguments.empty()) fail("set needs a setting name and a value");
            command.name = arguments[0];
            command.values.assign(arguments.begin() + 1, arguments.end());
            if (!is_known_setting(command.name)) {
                std::string names;
                for (const auto& setting : numeric_settings())
                    names += std::string(setting.name) + ", ";
                fail(fmt::format(
                    "unknown setting '{}' (known: {}generator, view, ao-method, radiosity-method, "
                    "light-intensity, light-colour, light-yaw, light-pitch, "
                    "light-position)",
                    command.name, names));
            }
            // Checked now against default settings and a spot light, so a bad
            // value stops the run before the window opens.
            RenderSettings trial;
            KeyLight light;
            light.kind = LightKind::spot;
            try {
                apply_set_command(command.name, command.values, trial, light);
            } catch (const InputError& error) {
                fail(error.what());
            }
        } else if (verb == "key") {
            command.kind = ScriptCommand::Kind::key;
            if (arguments.size() != 1) fail("key takes one key name");
            command.name = arguments[0];
            if (!find_key_binding(command.name)) {
                std::string keys;
                for (const auto& binding : key_bindings())
                    keys += std::string(keys.empty() ? "" : ", ") + std::string(binding.key);
                fail(fmt::format("unknown key '{}' (keys: {})", command.name, keys));
            }
        } else if (verb == "hold") {
            command.kind = ScriptCommand::Kind::hold;
            if (arguments.size() != 2) fail("hold takes a key and a number of frames");
            command.name = arguments[0];
            MoveKeys keys;
            if (!move_key_flag(keys, command.name))
                fail(fmt::format("hold: '{}' is not a movement key (W, A, S, D, Q, E)",
                                 command.name));
            command.numbers[0] = whole_number(arguments[1], 1, 100000, "hold: frames", fail);
        } else if (verb == "drag") {
            command.kind = ScriptCommand::Kind::drag;
            if (arguments.size() != 2) fail("drag takes DX DY in pixels");
            for (int i = 0; i < 2; ++i) {
                try {
                    command.numbers[i] = parse_float("drag", arguments[std::size_t(i)]);
                } catch (const InputError& error) {
                    fail(error.what());
                }
            }
        } else if (verb == "resize") {
            command.kind = ScriptCommand::Kind::resize;
            if (arguments.size() != 2) fail("resize takes WIDTH HEIGHT in pixels");
            command.numbers[0] =
                whole_number(arguments[0], 1, limits::max_image_side, "resize: width", fail);
            command.numbers[1] =
                whole_number(arguments[1], 1, limits::max_image_side, "resize: height", fail);
        } else if (verb == "capture") {
            command.kind = ScriptCommand::Kind::capture;
            if (arguments.size() != 1) fail("capture takes one path");
            std::string extension = std::filesystem::path(arguments[0]).extension().string();
            std::transform(extension.begin(), extension.end(), extension.begin(),
                           [](unsigned char c) { return char(std::tolower(c)); });
            if (extension != ".png") fail("capture: the path must end in .png");
            command.values = arguments;
        } else if (verb == "screenshot" || verb == "drop") {
            command.kind =
                verb == "drop" ? ScriptCommand::Kind::drop : ScriptCommand::Kind::screenshot;
            if (arguments.size() != 1) fail(fmt::format("{} takes one path", verb));
            command.values = arguments;
        } else if (verb == "quit") {
            command.kind = ScriptCommand::Kind::quit;
            if (!arguments.empty()) fail("quit takes no arguments");
        } else {
            fail(
                fmt::format("unknown command '{}' (set, key, hold, drag, resize, capture, "
                            "screenshot, drop, quit)",
                            verb));
        }
        commands.push_back(std::move(command));
    }
    return commands;
}

std::vector<ScriptCommand> load_script(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file || std::filesystem::is_directory(path))
        throw InputError(fmt::format("--script '{}': cannot read the file", path.string()));
    std::ostringstream text;
    text << file.rdbuf();
    return parse_script(text.str(), path.string());
}

}  // namespace deepgi
