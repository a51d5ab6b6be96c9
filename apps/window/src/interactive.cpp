// Interactive window and the hidden-window path. The renderer draws into its
// own textures exactly as headless; the window only shows the output texture.
#include "deepgi/interactive.hpp"

#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/image_io.hpp"
#include "deepgi/window_controls.hpp"

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <spiral/fileio.hpp>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <optional>
#include <vector>

namespace deepgi {

void render_hidden_window(const Scene& scene, const RenderSettings& settings, int frames,
                          bool follow_camera_path, const std::filesystem::path& output_png) {
    WindowContext window(settings.width, settings.height, "deepgi", false);
    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
    for (int frame = 0; frame < frames; ++frame) {
        renderer.render(follow_camera_path ? camera_on_path(scene.camera_path, frame)
                                           : scene.default_camera);
    }
    write_png(output_png, settings.width, settings.height, renderer.read_output_rgba8());
}

namespace {

namespace fs = std::filesystem;

// What the GLFW callbacks hand to the frame loop.
struct Inbox {
    std::vector<KeyAction> actions;
    std::vector<std::string> dropped;
    double scroll = 0.0;
};

// The key's name as the key table writes it, or "" for an unbound key.
std::string key_name(int key, int mods) {
    std::string name;
    if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) {
        name = std::string(1, char('A' + (key - GLFW_KEY_A)));
    } else {
        switch (key) {
            case GLFW_KEY_F1:
                name = "F1";
                break;
            case GLFW_KEY_F12:
                name = "F12";
                break;
            case GLFW_KEY_ESCAPE:
                name = "Escape";
                break;
            case GLFW_KEY_HOME:
                name = "Home";
                break;
            case GLFW_KEY_LEFT_BRACKET:
                name = "[";
                break;
            case GLFW_KEY_RIGHT_BRACKET:
                name = "]";
                break;
            case GLFW_KEY_COMMA:
                name = ",";
                break;
            case GLFW_KEY_PERIOD:
                name = ".";
                break;
            case GLFW_KEY_MINUS:
                name = "-";
                break;
            case GLFW_KEY_EQUAL:
                name = "=";
                break;
            default:
                return {};
        }
    }
    // Shift+G has no binding of its own and means G.
    if ((mods & GLFW_MOD_SHIFT) && find_key_binding("Shift+" + name)) return "Shift+" + name;
    return name;
}

void on_key(GLFWwindow* window, int key, int scancode, int action, int mods) {
    ImGui_ImplGlfw_KeyCallback(window, key, scancode, action, mods);
    if (action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
    if (const KeyBinding* binding = find_key_binding(key_name(key, mods))) {
        static_cast<Inbox*>(glfwGetWindowUserPointer(window))->actions.push_back(binding->action);
    }
}

void on_scroll(GLFWwindow* window, double x_offset, double y_offset) {
    ImGui_ImplGlfw_ScrollCallback(window, x_offset, y_offset);
    if (ImGui::GetIO().WantCaptureMouse) return;
    static_cast<Inbox*>(glfwGetWindowUserPointer(window))->scroll += y_offset;
}

void on_drop(GLFWwindow* window, int count, const char** paths) {
    auto* inbox = static_cast<Inbox*>(glfwGetWindowUserPointer(window));
    for (int i = 0; i < count; ++i) inbox->dropped.emplace_back(paths[i]);
}

struct FlyCamera {
    Camera camera;
    float speed = 1.0f;  // metres per second
    double last_x = 0.0;
    double last_y = 0.0;
    bool looking = false;
};

void update_fly_camera(GLFWwindow* window, FlyCamera& fly, float seconds) {
    const ImGuiIO& io = ImGui::GetIO();
    double x = 0.0;
    double y = 0.0;
    glfwGetCursorPos(window, &x, &y);
    const bool right_button = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    if (right_button && !io.WantCaptureMouse) {
        if (fly.looking) {
            const float radians_per_pixel = 0.004f;
            fly.camera.yaw += float(x - fly.last_x) * radians_per_pixel;
            fly.camera.pitch = std::clamp(
                fly.camera.pitch - float(y - fly.last_y) * radians_per_pixel, -1.5f, 1.5f);
        }
        fly.looking = true;
    } else {
        fly.looking = false;
    }
    fly.last_x = x;
    fly.last_y = y;
    if (io.WantCaptureKeyboard) return;
    const glm::vec3 forward = camera_forward(fly.camera);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    glm::vec3 move(0.0f);
    if (glfwGetKey(window, GLFW_KEY_W) == GLFW_PRESS) move += forward;
    if (glfwGetKey(window, GLFW_KEY_S) == GLFW_PRESS) move -= forward;
    if (glfwGetKey(window, GLFW_KEY_D) == GLFW_PRESS) move += right;
    if (glfwGetKey(window, GLFW_KEY_A) == GLFW_PRESS) move -= right;
    if (glfwGetKey(window, GLFW_KEY_E) == GLFW_PRESS) move.y += 1.0f;
    if (glfwGetKey(window, GLFW_KEY_Q) == GLFW_PRESS) move.y -= 1.0f;
    if (glm::length(move) > 0.0f)
        fly.camera.position += glm::normalize(move) * fly_step(seconds, fly.speed);
}

// A combo box over an enum's name table; true when the value changed.
template <class Enum>
bool enum_combo(const char* label, Enum& value) {
    bool changed = false;
    if (!ImGui::BeginCombo(label, std::string(to_string(value)).c_str())) return false;
    for (const auto& row : enum_names(Enum{})) {
        if (ImGui::Selectable(std::string(row.name).c_str(), row.value == value)) {
            changed = row.value != value;
            value = row.value;
        }
    }
    ImGui::EndCombo();
    return changed;
}

// Sliders for every numeric setting of one group, from the settings table. A
// length that follows the scene (`auto`) shows the value in use, greyed, and
// a checkbox; unticking it keeps that value as an explicit one.
void numeric_sliders(std::string_view group, RenderSettings& settings,
                     const RenderSettings& in_use) {
    for (const NumericSetting& setting : numeric_settings()) {
        if (setting.group != group) continue;
        ImGui::PushID(setting.name.data(), setting.name.data() + setting.name.size());
        const std::string label = std::string(setting.label);
        const ImGuiSliderFlags flags = setting.logarithmic ? ImGuiSliderFlags_Logarithmic : 0;
        if (accepts_auto(setting)) {
            bool follows_scene = setting.get(settings) == auto_length;
            if (ImGui::Checkbox("auto", &follows_scene))
                setting.set(settings, follows_scene ? auto_length : setting.get(in_use));
            if (ImGui::IsItemHovered()) {
                if (is_scene_length(setting))
                    ImGui::SetTooltip("%g x the scene's bounding radius", setting.scene_fraction);
                else
                    ImGui::SetTooltip("measured each frame (docs/deepgi.md, \"Exposure\")");
            }
            ImGui::SameLine();
        }
        if (accepts_auto(setting) && setting.get(settings) == auto_length) {
            float value = setting.get(in_use);
            ImGui::BeginDisabled();
            ImGui::SliderFloat(label.c_str(), &value, setting.slider_min, setting.slider_max,
                               "%.4g", flags);
            ImGui::EndDisabled();
        } else if (setting.integer) {
            int value = int(std::lround(setting.get(settings)));
            if (ImGui::SliderInt(label.c_str(), &value, int(setting.slider_min),
                                 int(setting.slider_max), "%d", flags))
                setting.set(settings, float(value));
        } else {
            float value = setting.get(settings);
            if (ImGui::SliderFloat(label.c_str(), &value, setting.slider_min, setting.slider_max,
                                   "%.3f", flags))
                setting.set(settings, value);
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("--%s", std::string(setting.name).c_str());
        ImGui::PopID();
    }
}

// "deepgi-2026-11-23_14-05-09" in local time; "-2", "-3" ... when taken.
fs::path dated_folder(const fs::path& parent) {
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    char stamp[64];
    std::strftime(stamp, sizeof stamp, "deepgi-%Y-%m-%d_%H-%M-%S", &local);
    fs::path folder = parent / stamp;
    for (int n = 2; fs::exists(folder); ++n) folder = parent / fmt::format("{}-{}", stamp, n);
    return folder;
}

// final.png plus every pass output as PFM, all appearing at once.
void write_screenshot(const Renderer& renderer, const fs::path& folder) {
    spiral::fileio::AtomicDirectory out(folder);
    const RenderSettings& settings = renderer.settings();
    const auto png = encode_png(settings.width, settings.height, renderer.read_output_rgba8());
    out.write_file("final.png", png.data(), png.size());
    for (const std::string& name : renderer.pass_output_names()) {
        const auto pfm = encode_pfm(renderer.read_pass_output(name));
        out.write_file(name + ".pfm", pfm.data(), pfm.size());
    }
    out.commit();
}

// Small horizontal bars, one per pass, scaled to the slowest; total below.
void timing_chart(const Renderer& renderer) {
    const auto& timings = renderer.last_timings();
    double total = 0.0;
    double slowest = 1e-9;
    for (const auto& timing : timings) {
        total += timing.milliseconds;
        slowest = std::max(slowest, timing.milliseconds);
    }
    ImGui::Text("per pass (%s)", renderer.timing_uses_cpu_clock() ? "CPU clock around glFinish"
                                                                  : "GL timer queries");
    for (const auto& timing : timings) {
        const std::string overlay = fmt::format("{} {:.2f} ms", timing.pass, timing.milliseconds);
        ImGui::ProgressBar(float(timing.milliseconds / slowest),
                           ImVec2(-1.0f, ImGui::GetTextLineHeight()), overlay.c_str());
    }
    ImGui::Text("total %.2f ms (%.1f fps at this cost)", total, total > 0.0 ? 1000.0 / total : 0.0);
}

// Everything the window owns besides GLFW and ImGui.
struct WindowState {
    explicit WindowState(const WindowOptions& window_options) : options(window_options) {}
    const WindowOptions& options;
    ShaderLoader loader = ShaderLoader::from_build_configuration();
    Scene scene;
    std::unique_ptr<Renderer> renderer;
    RenderSettings settings;
    KeyLight light;
    LightAngles light_angles_edit;
    Camera home_camera;  // what "reset camera" returns to
    FlyCamera fly;
    KeyState keys;
    bool show_panel = true;
    bool quit = false;
    std::string scene_error;  // last failed load, shown in red until the next load
    std::string settings_error;
    std::string screenshot_message;
};

float scene_size(const Scene& scene) {
    return std::max(glm::length(scene.bounds.max - scene.bounds.min), 1e-3f);
}

// Replaces scene and renderer only when both were made: a bad file keeps the
// old scene on screen.
void install_scene(WindowState& state, Scene scene, const std::string& camera) {
    const Camera home = camera.empty() ? scene.default_camera : find_file_camera(scene, camera);
    auto renderer = std::make_unique<Renderer>(scene, state.settings, state.loader);
    for (const std::string& line : describe_auto_lengths(
             state.settings, renderer->settings_in_use(), scene_bounding_radius(scene)))
        fmt::print("scene scale: {}\n", line);
    state.renderer = std::move(renderer);
    state.scene = std::move(scene);
    state.light = state.scene.key_light;
    state.light_angles_edit = light_angles(state.light.direction);
    state.home_camera = home;
    state.fly.camera = home;
    state.fly.speed = 0.25f * scene_size(state.scene);
}

void load_dropped(WindowState& state, const std::string& path) {
    try {
        install_scene(state, load_scene(path, state.options.scene_limits), {});
        state.scene_error.clear();
    } catch (const std::exception& error) {
        state.scene_error = fmt::format("could not load '{}': {}", path, error.what());
        fmt::print(stderr, "deepgi: {}\n", state.scene_error);
    }
}

void take_screenshot(WindowState& state, const fs::path& folder) {
    try {
        write_screenshot(*state.renderer, folder);
        state.screenshot_message = fmt::format("wrote {}", folder.string());
        fmt::print("deepgi: screenshot {}\n", folder.string());
    } catch (const std::exception& error) {
        state.screenshot_message = fmt::format("screenshot failed: {}", error.what());
        fmt::print(stderr, "deepgi: {}\n", state.screenshot_message);
    }
}

void handle_action(WindowState& state, KeyAction action) {
    if (apply_key_action(action, state.settings, state.keys)) return;
    switch (action) {
        case KeyAction::reset_camera:
            state.fly.camera = state.home_camera;
            break;
        case KeyAction::screenshot:
            take_screenshot(state, dated_folder(state.options.screenshot_directory));
            break;
        case KeyAction::toggle_panel:
            state.show_panel = !state.show_panel;
            break;
        case KeyAction::quit:
            state.quit = true;
            break;
        default:
            break;
    }
}

void draw_panel(WindowState& state, RenderSettings& wanted) {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    const float window_height = ImGui::GetIO().DisplaySize.y;
    ImGui::SetNextWindowSize(ImVec2(440, std::max(200.0f, window_height - 16.0f)),
                             ImGuiCond_FirstUseEver);
    // Resizable and collapsible (title bar arrow); F1 hides it altogether.
    if (!ImGui::Begin("deepgi (F1 hides)")) {
        ImGui::End();
        return;
    }
    // Room for the longest label right of the widgets, however wide the panel.
    ImGui::PushItemWidth(-150.0f);
    const auto builtin = builtin_scene_names();
    if (ImGui::BeginCombo("scene", state.scene.name.c_str())) {
        for (const std::string& name : builtin) {
            if (ImGui::Selectable(name.c_str(), name == state.scene.name) &&
                name != state.scene.name) {
                try {
                    install_scene(state, make_builtin_scene(name), {});
                    state.scene_error.clear();
                } catch (const std::exception& error) {
                    state.scene_error = error.what();
                }
            }
        }
        ImGui::EndCombo();
    }
    ImGui::TextDisabled("drop a .gltf/.glb file onto the window to load it");
    if (!state.scene_error.empty())
        ImGui::TextColored(ImVec4(1.0f, 0.35f, 0.3f, 1.0f), "%s", state.scene_error.c_str());
    if (!state.settings_error.empty())
        ImGui::TextColored(ImVec4(1.0f, 0.35f, 0.3f, 1.0f), "%s", state.settings_error.c_str());
    if (!state.screenshot_message.empty())
        ImGui::TextWrapped("%s", state.screenshot_message.c_str());

    if (ImGui::CollapsingHeader("frame", ImGuiTreeNodeFlags_DefaultOpen)) {
        enum_combo("generator (G)", wanted.generator);
        enum_combo("view (V)", wanted.view);
        enum_combo("timing", wanted.timing);
        // The exposure in use is measured, not resolved: the panel shows it
        // (greyed under auto) and unticking auto keeps it.
        RenderSettings in_use = state.renderer->settings_in_use();
        in_use.exposure = state.keys.exposure_in_use;
        numeric_sliders("frame", wanted, in_use);
        ImGui::Text("exposure in use %.4g (log-average luminance %.4g)", state.keys.exposure_in_use,
                    state.renderer->frame_statistics().log_average_luminance);
        if (wanted.view == DebugView::depth_layer0 || wanted.view == DebugView::depth_layer1) {
            const int layer = wanted.view == DebugView::depth_layer0 ? 0 : 1;
            const DepthRange range = state.renderer->depth_ranges()[std::size_t(layer)];
            ImGui::Text("depth view: layer %d, %.4g (white) to %.4g (dark grey)", layer,
                        range.near_depth, range.far_depth);
        }
    }
    if (ImGui::CollapsingHeader("ambient occlusion", ImGuiTreeNodeFlags_DefaultOpen)) {
        enum_combo("method (M)", wanted.ao.method);
        numeric_sliders("ao", wanted, state.renderer->settings_in_use());
    }
    if (ImGui::CollapsingHeader("radiosity and temporal filter", ImGuiTreeNodeFlags_DefaultOpen)) {
        enum_combo("radiosity method", wanted.radiosity.method);
        numeric_sliders("radiosity", wanted, state.renderer->settings_in_use());
    }
    if (ImGui::CollapsingHeader("bilateral blur (AO and radiosity)"))
        numeric_sliders("blur", wanted, state.renderer->settings_in_use());
    if (ImGui::CollapsingHeader("mirror reflections")) {
        ImGui::Checkbox("reflections", &wanted.reflection.enabled);
        numeric_sliders("reflection", wanted, state.renderer->settings_in_use());
    }
    if (ImGui::CollapsingHeader("light", ImGuiTreeNodeFlags_DefaultOpen)) {
        KeyLight& light = state.light;
        ImGui::Text("%s key light", light.kind == LightKind::spot    ? "spot"
                                    : light.kind == LightKind::point ? "point"
                                                                     : "directional");
        ImGui::SliderFloat("intensity", &light.intensity, 0.0f, 50.0f, "%.2f",
                           ImGuiSliderFlags_AlwaysClamp);
        ImGui::ColorEdit3("colour", &light.colour.x, ImGuiColorEditFlags_Float);
        bool turned = ImGui::SliderAngle("yaw", &state.light_angles_edit.yaw, -180.0f, 180.0f);
        turned |= ImGui::SliderAngle("pitch (below horizon)", &state.light_angles_edit.pitch,
                                     -90.0f, 90.0f);
        if (turned) light.direction = light_direction(state.light_angles_edit);
        if (light.kind != LightKind::directional) {
            const Bounds& bounds = state.scene.bounds;
            for (int axis = 0; axis < 3; ++axis) {
                const char* labels[] = {"position x", "position y", "position z"};
                ImGui::SliderFloat(labels[axis], &light.position[axis], bounds.min[axis],
                                   bounds.max[axis]);
            }
        }
        light.colour = glm::max(light.colour, glm::vec3(0.0f));
    }
    if (ImGui::CollapsingHeader("camera", ImGuiTreeNodeFlags_DefaultOpen)) {
        const float size = scene_size(state.scene);
        ImGui::SliderFloat("fly speed (m/s)", &state.fly.speed, 0.005f * size, 4.0f * size, "%.3f",
                           ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
        if (ImGui::Button("reset camera (R)")) state.fly.camera = state.home_camera;
        const Camera& camera = state.fly.camera;
        ImGui::Text("at (%.2f, %.2f, %.2f), yaw %.0f, pitch %.0f", camera.position.x,
                    camera.position.y, camera.position.z, glm::degrees(camera.yaw),
                    glm::degrees(camera.pitch));
        if (!state.renderer->history_valid()) ImGui::TextDisabled("history: none (fresh start)");
    }
    if (ImGui::CollapsingHeader("timings", ImGuiTreeNodeFlags_DefaultOpen))
        timing_chart(*state.renderer);
    if (ImGui::CollapsingHeader("keys")) {
        ImGui::TextWrapped("%s", std::string(movement_help()).c_str());
        for (const auto& binding : key_bindings())
            ImGui::Text("%-8s %s", std::string(binding.key).c_str(),
                        std::string(binding.description).c_str());
    }
    ImGui::PopItemWidth();
    ImGui::End();
}

// Runs the script commands of `frame`; false when one failed (the message
// is printed and the window closes with status 2).
bool run_script_commands(WindowState& state, const std::vector<ScriptCommand>& script,
                         std::size_t& next, int frame) {
    for (; next < script.size() && script[next].frame == frame; ++next) {
        const ScriptCommand& command = script[next];
        try {
            switch (command.kind) {
                case ScriptCommand::Kind::set:
                    apply_set_command(command.name, command.values, state.settings, state.light);
                    state.light_angles_edit = light_angles(state.light.direction);
                    break;
                case ScriptCommand::Kind::key:
                    handle_action(state, find_key_binding(command.name)->action);
                    break;
                case ScriptCommand::Kind::screenshot:
                    write_screenshot(*state.renderer, command.values[0]);
                    fmt::print("deepgi: screenshot {}\n", command.values[0]);
                    break;
                case ScriptCommand::Kind::drop:
                    load_dropped(state, command.values[0]);
                    break;
                case ScriptCommand::Kind::quit:
                    state.quit = true;
                    break;
            }
        } catch (const std::exception& error) {
            fmt::print(stderr, "deepgi: error: {}:{}: {}\n", state.options.script.string(),
                       command.line, error.what());
            return false;
        }
    }
    return true;
}

}  // namespace

int run_interactive(const WindowOptions& options, const RenderSettings& initial_settings) {
    // Parsed before the window opens, so a bad script costs no window.
    const std::vector<ScriptCommand> script =
        options.script.empty() ? std::vector<ScriptCommand>{} : load_script(options.script);
    const bool scripted = !options.script.empty();
    // F12 writes here: refuse a missing or unwritable directory now, not at
    // the first screenshot.
    spiral::fileio::check_directory_target(dated_folder(options.screenshot_directory));

    WindowState state(options);
    state.settings = initial_settings;
    Scene first_scene = load_scene(options.scene, options.scene_limits);
    if (!options.camera.empty()) find_file_camera(first_scene, options.camera);  // throws early

    WindowContext context(initial_settings.width, initial_settings.height,
                          fmt::format("deepgi - {}", first_scene.name), true);
    GLFWwindow* window = context.window();
    // A script steps at a fixed rate and should not wait for vertical sync.
    glfwSwapInterval(scripted ? 0 : 1);
    Inbox inbox;
    glfwSetWindowUserPointer(window, &inbox);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    glfwSetKeyCallback(window, on_key);        // both chain to ImGui's handlers
    glfwSetScrollCallback(window, on_scroll);  //
    glfwSetDropCallback(window, on_drop);
    ImGui_ImplOpenGL3_Init("#version 450 core");

    int status = 0;
    install_scene(state, std::move(first_scene), options.camera);
    double last_time = glfwGetTime();
    std::size_t next_command = 0;
    for (int frame = 0; !glfwWindowShouldClose(window) && !state.quit; ++frame) {
        glfwPollEvents();
        const double now = glfwGetTime();
        const float seconds = scripted ? 1.0f / 30.0f : float(now - last_time);
        last_time = now;

        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        for (KeyAction action : inbox.actions) handle_action(state, action);
        inbox.actions.clear();
        if (inbox.scroll != 0.0) {
            state.fly.speed *= float(std::pow(1.2, inbox.scroll));
            state.fly.speed = std::clamp(state.fly.speed, 0.005f * scene_size(state.scene),
                                         4.0f * scene_size(state.scene));
            inbox.scroll = 0.0;
        }
        for (const std::string& path : inbox.dropped) load_dropped(state, path);
        inbox.dropped.clear();
        update_fly_camera(window, state.fly, seconds);

        RenderSettings wanted = state.settings;
        if (state.show_panel) draw_panel(state, wanted);

        int width = 0;
        int height = 0;
        glfwGetFramebufferSize(window, &width, &height);
        if (width > 0 && height > 0) {
            wanted.width = width;
            wanted.height = height;
            // Sliders stay in range, but a Ctrl+click typed value may not:
            // keep the last valid settings and say why.
            try {
                state.renderer->set_settings(wanted);
                state.settings = wanted;
                state.settings_error.clear();
            } catch (const InputError& error) {
                state.settings_error = error.what();
            }
            try {
                state.renderer->set_key_light(state.light);
            } catch (const InputError& error) {
                state.settings_error = error.what();
                state.light = state.renderer->key_light();
            }
            state.renderer->render(state.fly.camera);
            // 32 bytes read after the frame (Renderer::frame_statistics), for
            // the panel and the exposure keys.
            state.keys.exposure_in_use = state.renderer->exposure_in_use();

            // Show the output texture: blit it onto the window's framebuffer.
            gl::Framebuffer source = gl::create_framebuffer();
            glNamedFramebufferTexture(source.get(), GL_COLOR_ATTACHMENT0,
                                      state.renderer->output_texture(), 0);
            glBlitNamedFramebuffer(source.get(), 0, 0, 0, width, height, 0, 0, width, height,
                                   GL_COLOR_BUFFER_BIT, GL_NEAREST);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            glViewport(0, 0, width, height);
        }
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        glfwSwapBuffers(window);
        if (scripted && !run_script_commands(state, script, next_command, frame)) {
            status = 2;
            break;
        }
    }

    state.renderer.reset();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    return status;
}

}  // namespace deepgi
