#pragma once
// What the interactive window does with keys and with a --script file,
// without GL or GLFW: the key table (shown in the panel and in --help), the
// settings the keys change, the script parser and the fly-camera step. The
// window (interactive.cpp) maps GLFW events onto these.
#include "deepgi/scene.hpp"
#include "deepgi/settings.hpp"

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace deepgi {

enum class KeyAction {
    next_view,
    previous_view,
    next_generator,
    next_ao_method,
    ao_radius_down,
    ao_radius_up,
    radiosity_radius_down,
    radiosity_radius_up,
    exposure_down,
    exposure_up,
    toggle_layers,    // AO and radiosity together: 1 <-> 2 layers
    toggle_temporal,  // radiosity alpha 0 <-> the value before
    reset_camera,
    screenshot,
    toggle_panel,
    quit,
};

struct KeyBinding {
    std::string_view key;  // as written in the panel, --help and a script: "Shift+V", "F12"
    KeyAction action;
    std::string_view description;
};

// Every key press the window reacts to (held movement keys are listed in
// movement_help()).
std::span<const KeyBinding> key_bindings();
// nullptr for a key that is not bound.
const KeyBinding* find_key_binding(std::string_view key);
// "WASD move, Q/E down/up, ..." for the keys held or dragged.
std::string_view movement_help();
// One line per key: "  F12        screenshot ...".
std::string key_help_text();

// The window's state the keys change besides the settings.
struct KeyState {
    float remembered_alpha = RadiositySettings{}.alpha;  // for toggle_temporal
    // The exposure the last frame used (Renderer::exposure_in_use()): under
    // `auto`, - and = switch to a manual exposure starting from it.
    float exposure_in_use = 1.0f;
    // The lengths the last frame resolved (Renderer::settings_in_use()): under
    // `auto`, [ ] , . switch to a manual radius starting from the one in use.
    RenderSettings in_use;
};

// Applies a settings key to `settings` (the result stays valid); returns
// false for the actions the window handles itself (camera, screenshot,
// panel, quit).
bool apply_key_action(KeyAction action, RenderSettings& settings, KeyState& state);

// Fly camera: the distance moved this frame. Frame time is capped at
// max_fly_step_seconds, so that a slow frame (5 fps on llvmpipe) moves no
// further than a 20 fps frame and a held key cannot carry the camera through
// a wall in one step.
inline constexpr float max_fly_step_seconds = 0.05f;
float fly_step(float frame_seconds, float metres_per_second);

// Mouse look: a right-button drag of (dx, dy) pixels turns the camera by
// look_radians_per_pixel each, pitch kept within +-max_look_pitch. The
// window's mouse and a script's `drag` both go through it.
inline constexpr float look_radians_per_pixel = 0.004f;
inline constexpr float max_look_pitch = 1.5f;
void mouse_look(Camera& camera, float dx, float dy);

// The movement keys held this frame (W/A/S/D, Q/E).
struct MoveKeys {
    bool forward = false, back = false, left = false, right = false, down = false, up = false;
};
// "W" "A" "S" "D" "Q" "E": the key's flag in `keys`; nullptr for another key.
bool* move_key_flag(MoveKeys& keys, std::string_view key);
// Moves the camera `step` along the held keys' direction (forward is where it
// looks, up is +Y); no key, no move.
void fly_move(Camera& camera, const MoveKeys& keys, float step);

// ---- --script FILE ----
// One command a line; '#' starts a comment; blank lines are ignored:
//   frame N set NAME VALUE...   a numeric setting (numeric_settings() names),
//                               generator, view, ao-method, radiosity-method, or the light:
//                               light-intensity I, light-colour R G B,
//                               light-yaw DEG, light-pitch DEG,
//                               light-position X Y Z (spot lights)
//   frame N key KEY             a key press from key_bindings()
//   frame N hold KEY FRAMES     a movement key (W A S D Q E) held for the next FRAMES frames
//   frame N drag DX DY          a right-button mouse drag of DX, DY pixels (look)
//   frame N resize W H          the window resized to W x H pixels
//   frame N capture FILE.png    the window as shown, panel included
//   frame N screenshot DIR      the PNG, every pass output's PFM and camera.txt into DIR
//   frame N drop FILE           as if FILE were dropped onto the window
//   frame N quit                close the window (exit status 0)
// Commands of frame N run after frame N (counted from 0) was rendered, in
// file order; frame numbers never decrease. The script steps frames at a
// fixed 1/30 s so a run repeats exactly.
struct ScriptCommand {
    enum class Kind { set, key, hold, drag, resize, capture, screenshot, drop, quit };
    int frame = 0;
    Kind kind = Kind::quit;
    std::string name;                 // set: the setting; key, hold: the key
    std::vector<std::string> values;  // set: its value(s); screenshot, drop, capture: the path
    double numbers[2] = {0.0, 0.0};   // hold: frames; drag: dx, dy; resize: width, height
    int line = 0;
};

// Throws InputError "SOURCE:LINE: <problem>" naming the first bad line.
std::vector<ScriptCommand> parse_script(std::string_view text, std::string_view source);
// Reads and parses a file; a missing file is an InputError too.
std::vector<ScriptCommand> load_script(const std::filesystem::path& path);

// The light as the panel edits it: yaw about +Y and pitch below the horizon,
// in radians, for the direction the light travels.
struct LightAngles {
    float yaw = 0.0f;
    float pitch = 0.0f;
};
LightAngles light_angles(glm::vec3 direction);
glm::vec3 light_direction(LightAngles angles);

// Applies a `set` command to the settings or the light; throws InputError
// "<name>: <problem>" when the value is invalid (validate()'s message for
// settings).
void apply_set_command(const std::string& name, const std::vector<std::string>& values,
                       RenderSettings& settings, KeyLight& light);

}  // namespace deepgi
