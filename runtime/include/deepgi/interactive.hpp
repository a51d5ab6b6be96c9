#pragma once
#include "deepgi/renderer.hpp"

#include <filesystem>
#include <string>

namespace deepgi {

// Opens a window with a fly camera (WASD, right mouse button to look), debug
// view cycling (V / Shift+V), generator cycling (G) and a Dear ImGui panel.
// Returns the process exit status.
int run_interactive(const std::string& scene_name, const RenderSettings& settings);

// Renders `frames` frames of the default camera into a hidden GLFW window's
// context and writes the PNG: the same image as the EGL path, used to test
// that both contexts agree.
void render_hidden_window(const Scene& scene, const RenderSettings& settings, int frames,
                          bool follow_camera_path, const std::filesystem::path& output_png);

}  // namespace deepgi
