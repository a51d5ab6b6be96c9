#pragma once
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"

#include <filesystem>
#include <string>

namespace deepgi {

struct WindowOptions {
    std::string scene = "cornell";  // built-in name or glTF file
    SceneLimits scene_limits;       // also for files dropped onto the window
    std::string camera;             // a file camera's name or index; empty: the default
    std::filesystem::path script;   // --script FILE (window_controls.hpp); empty: none
    std::filesystem::path screenshot_directory = ".";  // where F12's dated folders go
    std::filesystem::path shaders;  // --shaders DIR, searched before the build's; empty: none
};

// Opens a window with a fly camera, the keys of window_controls.hpp, a Dear
// ImGui panel that edits every setting and the light live, drag-and-drop of
// glTF files and screenshots. Returns the process exit status.
int run_interactive(const WindowOptions& options, const RenderSettings& settings);

// Renders `frames` frames of the default camera into a hidden GLFW window's
// context and writes the PNG: the same image as the EGL path, used to test
// that both contexts agree.
void render_hidden_window(const Scene& scene, const RenderSettings& settings, int frames,
                          bool follow_camera_path, const std::filesystem::path& output_png,
                          const std::filesystem::path& shaders = {});

}  // namespace deepgi
