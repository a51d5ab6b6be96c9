// Interactive window and the hidden-window path. The renderer draws into its
// own textures exactly as headless; the window only shows the output texture.
#include "deepgi/interactive.hpp"

#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/image_io.hpp"
#include "deepgi/window_controls.hpp"
#include "window_state.hpp"

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
                          bool follow_camera_path, const std::filesystem::path& output_png,
                          const std::filesystem::path& shaders) {
    WindowContext window(settings.width, settings.height, "deepgi", false);
    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration(shaders));
    for (int frame = 0; frame < frames; ++frame) {
        // As headless: the next camera too, for the delay generator.
        if (follow_camera_path)
            renderer.render(camera_on_path(scene.camera_path, frame),
                            camera_on_path(scene.camera_path, frame + 1));
        else
            renderer.render(scene.default_camera, scene.default_camera);
    }
    write_png(output_png, settings.width, settings.height, renderer.read_output_rgba8());
}

namespace {

namespace fs = std::filesystem;

// A movement key a script holds for a number of frames.
struct ScriptHold {
    std::string key;
    int frames_left = 0;
};

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

// Movement keys held in the window or by a script's `hold`.
MoveKeys held_move_keys(GLFWwindow* window, const std::vector<ScriptHold>& holds) {
    MoveKeys keys;
    if (!ImGui::GetIO().WantCaptureKeyboard) {
        for (const char* key : {"W", "A", "S", "D", "Q", "E"})
            if (glfwGetKey(window, GLFW_KEY_A + (key[0] - 'A')) == GLFW_PRESS)
                *move_key_flag(keys, key) = true;
    }
    for (const ScriptHold& hold : holds) *move_key_flag(keys, hold.key) = true;
    return keys;
}

void update_fly_camera(GLFWwindow* window, FlyCamera& fly, const MoveKeys& keys, float seconds) {
    double x = 0.0;
    double y = 0.0;
    glfwGetCursorPos(window, &x, &y);
    const bool right_button = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    if (right_button && !ImGui::GetIO().WantCaptureMouse) {
        if (fly.looking) mouse_look(fly.camera, float(x - fly.last_x), float(y - fly.last_y));
        fly.looking = true;
    } else {
        fly.looking = false;
    }
    fly.last_x = x;
    fly.last_y = y;
    fly_move(fly.camera, keys, fly_step(seconds, fly.speed));
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
// camera.txt holds the camera the image was rendered with, as --camera takes
// it, so that `deepgi --headless --camera "$(cat camera.txt)"` renders the view.
void write_screenshot(const Renderer& renderer, const Camera& camera, const fs::path& folder) {
    spiral::fileio::AtomicDirectory out(folder);
    const std::string pose = format_camera_pose(camera) + "\n";
    out.write_file("camera.txt", pose.data(), pose.size());
    const RenderSettings& settings = renderer.settings();
    const auto png = encode_png(settings.width, settings.height, renderer.read_output_rgba8());
    out.write_file("final.png", png.data(), png.size());
    for (const std::string& name : renderer.pass_output_names()) {
        const auto pfm = encode_pfm(renderer.read_pass_output(name));
        out.write_file(name + ".pfm", pfm.data(), pfm.size());
    }
    out.commit();
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
        write_screenshot(*state.renderer, state.rendered_camera, folder);
        state.screenshot_message = fmt::format("wrote {}", folder.string());
        fmt::print("deepgi: screenshot {}\n", folder.string());
    } catch (const std::exception& error) {
        state.screenshot_message = fmt::format("screenshot failed: {}", error.what());
        fmt::print(stderr, "deepgi: {}\n", state.screenshot_message);
    }
}

void handle_action(WindowState& state, KeyAction action) {
    // What the last frame used, for the keys that step from an `auto` value:
    // read on a key press only (the exposure is a 32-byte read-back), not
    // every frame.
    state.keys.exposure_in_use = state.renderer->exposure_in_use();
    state.keys.in_use = state.renderer->settings_in_use();
    if (apply_key_action(action, state.settings, state.keys)) {
        set_active_section(state, section_of_action(action, state.settings));
        return;
    }
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

// Runs the script commands of `frame`; false when one failed (the message
// is printed and the window closes with status 2).
bool run_script_commands(WindowState& state, GLFWwindow* window,
                         const std::vector<ScriptCommand>& script, std::size_t& next, int frame,
                         std::vector<ScriptHold>& holds) {
    for (; next < script.size() && script[next].frame == frame; ++next) {
        const ScriptCommand& command = script[next];
        try {
            switch (command.kind) {
                case ScriptCommand::Kind::set:
                    apply_set_command(command.name, command.values, state.settings, state.light);
                    state.light_angles_edit = light_angles(state.light.direction);
                    set_active_section(state, section_of_setting(command.name));
                    break;
                case ScriptCommand::Kind::hold:
                    holds.push_back({command.name, int(command.numbers[0])});
                    break;
                case ScriptCommand::Kind::drag:
                    mouse_look(state.fly.camera, float(command.numbers[0]),
                               float(command.numbers[1]));
                    break;
                case ScriptCommand::Kind::resize:
                    glfwSetWindowSize(window, int(command.numbers[0]), int(command.numbers[1]));
                    break;
                case ScriptCommand::Kind::capture:
                    break;  // done before the frame was shown (run_interactive)
                case ScriptCommand::Kind::key:
                    handle_action(state, find_key_binding(command.name)->action);
                    break;
                case ScriptCommand::Kind::screenshot:
                    write_screenshot(*state.renderer, state.rendered_camera, command.values[0]);
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

// The window's back buffer as shown (image and panel), opaque.
void capture_window(int width, int height, const fs::path& png) {
    std::vector<std::uint8_t> rgba(std::size_t(width) * std::size_t(height) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    for (std::size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;
    write_png(png, width, height, rgba);  // rows bottom to top, as GL reads them
}

}  // namespace

void install_scene(WindowState& state, Scene scene, const std::string& camera) {
    const Camera home = select_camera(scene, camera);
    auto renderer = std::make_unique<Renderer>(scene, state.settings, state.loader);
    for (const std::string& line :
         describe_auto_lengths(state.settings, renderer->settings_in_use(), scene_scale(scene)))
        fmt::print("scene scale: {}\n", line);
    state.renderer = std::move(renderer);
    state.scene = std::move(scene);
    state.light = state.scene.key_light;
    state.light_angles_edit = light_angles(state.light.direction);
    state.home_camera = home;
    state.fly.camera = home;
    state.delayed_camera.reset();  // a new scene has no last frame
    state.fly.speed = 0.25f * scene_size(state.scene);
}

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
    state.active_section = std::string(section_of_view(initial_settings.view));
    Scene first_scene = load_scene(options.scene, options.scene_limits);
    select_camera(first_scene, options.camera);  // a bad --camera throws before the window

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
    // An opaque panel: through the default 94% the image showed, and a bright
    // spot behind it (cornell's ceiling lamp, beside the "scene" label at
    // 640x360) read as a stray grey box.
    ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 1.0f;
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    glfwSetKeyCallback(window, on_key);        // both chain to ImGui's handlers
    glfwSetScrollCallback(window, on_scroll);  //
    glfwSetDropCallback(window, on_drop);
    ImGui_ImplOpenGL3_Init("#version 450 core");

    int status = 0;
    install_scene(state, std::move(first_scene), options.camera);
    double last_time = glfwGetTime();
    std::size_t next_command = 0;
    std::vector<ScriptHold> holds;
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
        update_fly_camera(window, state.fly, held_move_keys(window, holds), seconds);
        for (ScriptHold& hold : holds) --hold.frames_left;
        std::erase_if(holds, [](const ScriptHold& hold) { return hold.frames_left <= 0; });

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
            // The delay generator shows last frame's fly camera, so that
            // this frame's camera is the next one it peels against.
            const Camera shown = state.settings.generator == Generator::delay
                                     ? state.delayed_camera.value_or(state.fly.camera)
                                     : state.fly.camera;
            state.renderer->render(shown, state.fly.camera);
            state.rendered_camera = shown;
            state.delayed_camera = state.fly.camera;

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
        // A script's captures read the back buffer before it is shown.
        for (std::size_t i = next_command; i < script.size() && script[i].frame == frame; ++i) {
            if (script[i].kind != ScriptCommand::Kind::capture || width <= 0 || height <= 0)
                continue;
            try {
                capture_window(width, height, script[i].values[0]);
                fmt::print("deepgi: capture {}\n", script[i].values[0]);
            } catch (const std::exception& error) {
                fmt::print(stderr, "deepgi: error: {}:{}: {}\n", options.script.string(),
                           script[i].line, error.what());
                status = 2;
                state.quit = true;
            }
        }
        glfwSwapBuffers(window);
        if (scripted && !run_script_commands(state, window, script, next_command, frame, holds)) {
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
