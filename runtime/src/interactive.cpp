// Interactive window and the hidden-window path. The renderer draws into its
// own textures exactly as headless; the window only shows the output texture.
#include "deepgi/interactive.hpp"

#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>
#include <memory>

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

struct FlyCamera {
    Camera camera;
    double last_x = 0.0;
    double last_y = 0.0;
    bool looking = false;
};

void update_fly_camera(GLFWwindow* window, FlyCamera& fly, float seconds, float speed) {
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
    if (glm::length(move) > 0.0f) fly.camera.position += glm::normalize(move) * speed * seconds;
}

struct KeyEvents {
    int view_steps = 0;
    int generator_steps = 0;
};

void on_key(GLFWwindow* window, int key, int scancode, int action, int mods) {
    ImGui_ImplGlfw_KeyCallback(window, key, scancode, action, mods);
    if (action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
    auto* events = static_cast<KeyEvents*>(glfwGetWindowUserPointer(window));
    if (key == GLFW_KEY_V) events->view_steps += (mods & GLFW_MOD_SHIFT) ? -1 : 1;
    if (key == GLFW_KEY_G) events->generator_steps += 1;
    if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(window, GLFW_TRUE);
}

// The enum `steps` rows further along its name table, wrapping around.
template <class Enum>
Enum step_enum(Enum value, int steps) {
    const auto table = enum_names(Enum{});
    const int count = int(table.size());
    int current = 0;
    for (int i = 0; i < count; ++i)
        if (table[std::size_t(i)].value == value) current = i;
    return table[std::size_t(((current + steps) % count + count) % count)].value;
}

// A combo box over an enum's name table.
template <class Enum>
void enum_combo(const char* label, Enum& value) {
    if (!ImGui::BeginCombo(label, std::string(to_string(value)).c_str())) return;
    for (const auto& row : enum_names(Enum{})) {
        if (ImGui::Selectable(std::string(row.name).c_str(), row.value == value)) value = row.value;
    }
    ImGui::EndCombo();
}

}  // namespace

int run_interactive(const std::string& scene_name, const RenderSettings& initial_settings) {
    Scene scene = load_scene(scene_name);
    WindowContext context(initial_settings.width, initial_settings.height,
                          fmt::format("deepgi - {}", scene.name), true);
    GLFWwindow* window = context.window();
    glfwSwapInterval(1);
    KeyEvents key_events;
    glfwSetWindowUserPointer(window, &key_events);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    glfwSetKeyCallback(window, on_key);  // chains to ImGui's handler
    ImGui_ImplOpenGL3_Init("#version 450 core");

    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    RenderSettings settings = initial_settings;
    auto renderer = std::make_unique<Renderer>(scene, settings, loader);
    FlyCamera fly{scene.default_camera};
    const float scene_size = glm::length(scene.bounds.max - scene.bounds.min);
    const auto builtin = builtin_scene_names();
    int scene_choice = -1;
    for (std::size_t i = 0; i < builtin.size(); ++i) {
        if (builtin[i] == scene.name) scene_choice = int(i);
    }
    float light_yaw = std::atan2(scene.key_light.direction.x, -scene.key_light.direction.z);
    float light_pitch = std::asin(std::clamp(-scene.key_light.direction.y, -1.0f, 1.0f));
    double last_time = glfwGetTime();

    while (!glfwWindowShouldClose(window)) {
        glfwPollEvents();
        const double now = glfwGetTime();
        const float seconds = float(now - last_time);
        last_time = now;

        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        update_fly_camera(window, fly, seconds, 0.25f * scene_size);

        RenderSettings wanted = settings;
        wanted.view = step_enum(wanted.view, key_events.view_steps);
        wanted.generator = step_enum(wanted.generator, key_events.generator_steps);
        key_events.view_steps = 0;
        key_events.generator_steps = 0;

        ImGui::Begin("deepgi");
        {
            std::string label = scene_choice >= 0 ? builtin[std::size_t(scene_choice)] : scene.name;
            if (ImGui::BeginCombo("scene", label.c_str())) {
                for (std::size_t i = 0; i < builtin.size(); ++i) {
                    if (ImGui::Selectable(builtin[i].c_str(), int(i) == scene_choice) &&
                        int(i) != scene_choice) {
                        scene_choice = int(i);
                        scene = make_builtin_scene(builtin[i]);
                        renderer = std::make_unique<Renderer>(scene, settings, loader);
                        fly.camera = scene.default_camera;
                        light_yaw =
                            std::atan2(scene.key_light.direction.x, -scene.key_light.direction.z);
                        light_pitch =
                            std::asin(std::clamp(-scene.key_light.direction.y, -1.0f, 1.0f));
                    }
                }
                ImGui::EndCombo();
            }
        }
        enum_combo("generator (G)", wanted.generator);
        ImGui::SliderFloat("min separation (m)", &wanted.min_separation, 0.0f, 2.0f);
        ImGui::SliderFloat("exposure", &wanted.exposure, 0.05f, 8.0f, "%.2f",
                           ImGuiSliderFlags_Logarithmic);
        enum_combo("view (V)", wanted.view);
        if (ImGui::CollapsingHeader("light", ImGuiTreeNodeFlags_DefaultOpen)) {
            ImGui::SliderFloat("intensity", &scene.key_light.intensity, 0.0f, 50.0f);
            ImGui::ColorEdit3("colour", &scene.key_light.colour.x);
            bool moved = ImGui::SliderAngle("direction yaw", &light_yaw, -180.0f, 180.0f);
            moved |= ImGui::SliderAngle("direction pitch", &light_pitch, 5.0f, 90.0f);
            if (moved) {
                scene.key_light.direction = {std::cos(light_pitch) * std::sin(light_yaw),
                                             -std::sin(light_pitch),
                                             -std::cos(light_pitch) * std::cos(light_yaw)};
            }
            if (ImGui::Button("apply light"))
                renderer = std::make_unique<Renderer>(scene, settings, loader);
        }
        ImGui::Separator();
        ImGui::Text("timings (%s)", renderer->timing_uses_cpu_clock() ? "CPU clock around glFinish"
                                                                      : "GL timer queries");
        double total = 0.0;
        for (const auto& timing : renderer->last_timings()) {
            ImGui::Text("%-14s %7.2f ms", timing.pass.c_str(), timing.milliseconds);
            total += timing.milliseconds;
        }
        ImGui::Text("%-14s %7.2f ms", "total", total);
        ImGui::Text("WASD/QE move, right mouse look, V/Shift+V view, G generator");
        ImGui::End();

        int width = 0;
        int height = 0;
        glfwGetFramebufferSize(window, &width, &height);
        if (width > 0 && height > 0) {
            wanted.width = width;
            wanted.height = height;
            renderer->set_settings(wanted);
            settings = wanted;
            renderer->render(fly.camera);

            // Show the output texture: blit it onto the window's framebuffer.
            gl::Framebuffer source = gl::create_framebuffer();
            glNamedFramebufferTexture(source.get(), GL_COLOR_ATTACHMENT0,
                                      renderer->output_texture(), 0);
            glBlitNamedFramebuffer(source.get(), 0, 0, 0, width, height, 0, 0, width, height,
                                   GL_COLOR_BUFFER_BIT, GL_NEAREST);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            glViewport(0, 0, width, height);
        }
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        glfwSwapBuffers(window);
    }

    renderer.reset();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    return 0;
}

}  // namespace deepgi
