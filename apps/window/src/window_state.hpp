#pragma once
// The window's state, shared by the frame loop (interactive.cpp) and the
// panel (window_panel.cpp). Private to the window library.
#include "deepgi/interactive.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/window_controls.hpp"

#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace deepgi {

struct FlyCamera {
    Camera camera;
    float speed = 1.0f;  // metres per second
    double last_x = 0.0;
    double last_y = 0.0;
    bool looking = false;
};

// Everything the window owns besides GLFW and ImGui.
struct WindowState {
    explicit WindowState(const WindowOptions& window_options) : options(window_options) {}
    const WindowOptions& options;
    ShaderLoader loader = ShaderLoader::from_build_configuration(options.shaders);
    Scene scene;
    std::unique_ptr<Renderer> renderer;
    RenderSettings settings;
    KeyLight light;
    LightAngles light_angles_edit;
    Camera home_camera;      // what "reset camera" returns to
    Camera rendered_camera;  // the camera of the frame on screen (camera.txt)
    FlyCamera fly;
    // The fly camera of the last frame: with the delay generator the window
    // shows it, one frame late, so that this frame's camera is the next one.
    std::optional<Camera> delayed_camera;
    KeyState keys;
    bool show_panel = true;
    bool quit = false;
    std::string scene_error;  // last failed load, shown in red until the next load
    std::string settings_error;
    std::string screenshot_message;
    // The panel section in use ("frame", "ao", "radiosity", "blur",
    // "reflection", "light", "camera"): it opens when it changes, so a key
    // or a script edit shows its slider; the others start collapsed.
    std::string active_section;
    bool active_section_changed = true;
    // The display size the panel was last fitted to; a new size fits it again.
    float panel_fitted_width = 0.0f;
    float panel_fitted_height = 0.0f;
    float timings_height = 0.0f;  // measured on the last frame, pinned at the bottom
};

float scene_size(const Scene& scene);

// The panel section of a settings row group or script setting name.
std::string_view section_of_view(DebugView view);
std::string_view section_of_setting(std::string_view name);
std::string_view section_of_action(KeyAction action, const RenderSettings& after);
void set_active_section(WindowState& state, std::string_view section);

// Replaces scene and renderer only when both were made: a bad file keeps the
// old scene on screen. `camera` as --camera takes it.
void install_scene(WindowState& state, Scene scene, const std::string& camera);

// The settings panel; edits go to `wanted` and to the state's light and camera.
void draw_panel(WindowState& state, RenderSettings& wanted);

}  // namespace deepgi
