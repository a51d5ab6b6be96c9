// The window's settings panel (Dear ImGui): the sections built from the
// settings rows, the light and camera, and the per-pass timings pinned at
// the bottom. Its size follows the window's.
#include "window_state.hpp"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <string>

namespace deepgi {

namespace {

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

// `text` cut (with a trailing '~') to fit `width` pixels.
std::string fit_text(std::string text, float width) {
    if (ImGui::CalcTextSize(text.c_str()).x <= width) return text;
    while (text.size() > 1 && ImGui::CalcTextSize((text + "~").c_str()).x > width) text.pop_back();
    return text + "~";
}

// The label right of the last widget, cut to the room left in a narrow
// panel (the slider's tooltip says it whole).
void side_label(const std::string& label) {
    ImGui::SameLine(0.0f, ImGui::GetStyle().ItemInnerSpacing.x);
    ImGui::TextUnformatted(fit_text(label, ImGui::GetContentRegionAvail().x).c_str());
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
        const char* id = "##value";
        const ImGuiSliderFlags flags = setting.logarithmic ? ImGuiSliderFlags_Logarithmic : 0;
        if (accepts_auto(setting)) {
            bool follows_scene = setting.get(settings) == auto_length;
            if (ImGui::Checkbox("auto", &follows_scene))
                setting.set(settings, follows_scene ? auto_length : setting.get(in_use));
            if (ImGui::IsItemHovered()) {
                if (is_scene_length(setting) && setting.extent_fraction > 0.0f)
                    ImGui::SetTooltip(
                        "%g x the scene's bounding radius, at most %g x its smallest extent",
                        setting.scene_fraction, setting.extent_fraction);
                else if (is_scene_length(setting))
                    ImGui::SetTooltip("%g x the scene's bounding radius", setting.scene_fraction);
                else
                    ImGui::SetTooltip("measured each frame (docs/deepgi.md, \"Exposure\")");
            }
            ImGui::SameLine();
        }
        if (accepts_auto(setting) && setting.get(settings) == auto_length) {
            float value = setting.get(in_use);
            ImGui::BeginDisabled();
            ImGui::SliderFloat(id, &value, setting.slider_min, setting.slider_max, "%.4g", flags);
            ImGui::EndDisabled();
        } else if (setting.integer) {
            int value = int(std::lround(setting.get(settings)));
            if (ImGui::SliderInt(id, &value, int(setting.slider_min), int(setting.slider_max), "%d",
                                 flags))
                setting.set(settings, float(value));
        } else {
            float value = setting.get(settings);
            if (ImGui::SliderFloat(id, &value, setting.slider_min, setting.slider_max, "%.3f",
                                   flags))
                setting.set(settings, value);
        }
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
            ImGui::SetTooltip("%s (--%s)", label.c_str(), std::string(setting.name).c_str());
        side_label(label);
        ImGui::PopID();
    }
}

// One bar per pass in two columns, scaled to the slowest, the total on the
// heading line: short enough to stay on screen at 640x360.
void timing_chart(const Renderer& renderer) {
    const auto& timings = renderer.last_timings();
    double total = 0.0;
    double slowest = 1e-9;
    for (const auto& timing : timings) {
        total += timing.milliseconds;
        slowest = std::max(slowest, timing.milliseconds);
    }
    ImGui::Text("ms per pass, total %.2f", total);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s", renderer.timing_uses_cpu_clock() ? "CPU clock around glFinish"
                                                                 : "GL timer queries");
    // Rows packed tight: the chart has to leave room for the sections.
    ImGui::PushStyleVar(ImGuiStyleVar_ItemSpacing, ImVec2(4.0f, 1.0f));
    ImGui::PushStyleVar(ImGuiStyleVar_CellPadding, ImVec2(2.0f, 1.0f));
    if (!ImGui::BeginTable("timings", 2, ImGuiTableFlags_SizingStretchSame)) {
        ImGui::PopStyleVar(2);
        return;
    }
    for (const auto& timing : timings) {
        ImGui::TableNextColumn();
        const std::string full = fmt::format("{} {:.2f}", timing.pass, timing.milliseconds);
        const std::string ms = fmt::format(" {:.1f}", timing.milliseconds);
        const float room = ImGui::GetContentRegionAvail().x - ImGui::CalcTextSize(ms.c_str()).x -
                           2.0f * ImGui::GetStyle().FramePadding.x;
        const std::string overlay = fit_text(timing.pass, room) + ms;
        ImGui::ProgressBar(float(timing.milliseconds / slowest),
                           ImVec2(-FLT_MIN, ImGui::GetTextLineHeight()), overlay.c_str());
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s ms", full.c_str());
    }
    ImGui::EndTable();
    ImGui::PopStyleVar(2);
}

// A collapsing header that opens when its section became the one in use.
bool section(const WindowState& state, const char* label, std::string_view id) {
    if (state.active_section_changed && state.active_section == id)
        ImGui::SetNextItemOpen(true, ImGuiCond_Always);
    return ImGui::CollapsingHeader(label);
}

void light_section(WindowState& state) {
    KeyLight& light = state.light;
    ImGui::Text("%s key light", light.kind == LightKind::spot    ? "spot"
                                : light.kind == LightKind::point ? "point"
                                                                 : "directional");
    ImGui::SliderFloat("intensity", &light.intensity, 0.0f, 50.0f, "%.2f",
                       ImGuiSliderFlags_AlwaysClamp);
    ImGui::ColorEdit3("colour", &light.colour.x, ImGuiColorEditFlags_Float);
    bool turned = ImGui::SliderAngle("yaw", &state.light_angles_edit.yaw, -180.0f, 180.0f);
    turned |=
        ImGui::SliderAngle("pitch (below horizon)", &state.light_angles_edit.pitch, -90.0f, 90.0f);
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

void camera_section(WindowState& state) {
    const float size = scene_size(state.scene);
    ImGui::SliderFloat("fly speed (m/s)", &state.fly.speed, 0.005f * size, 4.0f * size, "%.3f",
                       ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
    if (ImGui::Button("reset camera (R)")) state.fly.camera = state.home_camera;
    const Camera& camera = state.fly.camera;
    ImGui::TextWrapped("at (%.2f, %.2f, %.2f), yaw %.0f, pitch %.0f", camera.position.x,
                       camera.position.y, camera.position.z, glm::degrees(camera.yaw),
                       glm::degrees(camera.pitch));
    if (!state.renderer->history_valid()) ImGui::TextDisabled("history: none (fresh start)");
}

void scene_combo(WindowState& state) {
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
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("or drop a .gltf/.glb file onto the window");
}

}  // namespace

void draw_panel(WindowState& state, RenderSettings& wanted) {
    // Fitted to the window whenever its size changes: about a third of the
    // width, capped, and the full height; in between it can be resized.
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    if (display.x != state.panel_fitted_width || display.y != state.panel_fitted_height) {
        const float margin = 8.0f;
        const float width = std::min(std::clamp(0.35f * display.x, 260.0f, 420.0f),
                                     std::max(display.x - 2.0f * margin, 1.0f));
        ImGui::SetNextWindowPos(ImVec2(margin, margin), ImGuiCond_Always);
        ImGui::SetNextWindowSize(ImVec2(width, std::max(display.y - 2.0f * margin, 1.0f)),
                                 ImGuiCond_Always);
        state.panel_fitted_width = display.x;
        state.panel_fitted_height = display.y;
    }
    // Collapsible (title bar arrow); F1 hides it altogether.
    // The sections scroll inside; the panel itself never does.
    if (!ImGui::Begin("deepgi (F1 hides)", nullptr,
                      ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse)) {
        ImGui::End();
        return;
    }
    // Room for the labels right of the widgets, however narrow the panel.
    const float label_room = std::min(150.0f, 0.5f * ImGui::GetContentRegionAvail().x);
    ImGui::PushItemWidth(-label_room);
    scene_combo(state);
    const ImVec4 red(1.0f, 0.35f, 0.3f, 1.0f);
    if (!state.scene_error.empty()) ImGui::TextColored(red, "%s", state.scene_error.c_str());
    if (!state.settings_error.empty()) ImGui::TextColored(red, "%s", state.settings_error.c_str());
    if (!state.screenshot_message.empty())
        ImGui::TextWrapped("%s", state.screenshot_message.c_str());

    // The sections scroll; the timings below them stay in view.
    const float timings_height =
        state.timings_height > 0.0f ? state.timings_height : 9.0f * ImGui::GetFrameHeight();
    ImGui::BeginChild("sections", ImVec2(0.0f, -timings_height));
    ImGui::PushItemWidth(-label_room);  // item widths are per window, the child's too
    const RenderSettings& in_use = state.renderer->settings_in_use();
    if (section(state, "frame", "frame")) {
        enum_combo("generator (G)", wanted.generator);
        enum_combo("view (V)", wanted.view);
        enum_combo("timing", wanted.timing);
        // The exposure in use is measured, not resolved: the panel shows it
        // (greyed under auto) and unticking auto keeps it.
        // One read-back of the last frame's statistics, while this section is open.
        const FrameStatistics statistics = state.renderer->frame_statistics();
        RenderSettings frame_in_use = in_use;
        frame_in_use.exposure = statistics.exposure;
        numeric_sliders("frame", wanted, frame_in_use);
        ImGui::Text("exposure in use %.4g (log-average luminance %.4g)", statistics.exposure,
                    statistics.log_average_luminance);
        if (wanted.view == DebugView::depth_layer0 || wanted.view == DebugView::depth_layer1) {
            const int layer = wanted.view == DebugView::depth_layer0 ? 0 : 1;
            const DepthRange range = statistics.depth_ranges[std::size_t(layer)];
            ImGui::Text("depth view: layer %d, %.4g (white) to %.4g (dark grey)", layer,
                        range.near_depth, range.far_depth);
        }
    }
    if (section(state, "ambient occlusion", "ao")) {
        enum_combo("method (M)", wanted.ao.method);
        numeric_sliders("ao", wanted, in_use);
    }
    if (section(state, "radiosity and temporal filter", "radiosity")) {
        enum_combo("radiosity method", wanted.radiosity.method);
        numeric_sliders("radiosity", wanted, in_use);
    }
    if (section(state, "bilateral blur (AO and radiosity)", "blur"))
        numeric_sliders("blur", wanted, in_use);
    if (section(state, "mirror reflections", "reflection")) {
        ImGui::Checkbox("reflections", &wanted.reflection.enabled);
        numeric_sliders("reflection", wanted, in_use);
    }
    if (section(state, "light", "light")) light_section(state);
    if (section(state, "camera", "camera")) camera_section(state);
    if (section(state, "keys", "keys")) {
        ImGui::TextWrapped("%s", std::string(movement_help()).c_str());
        for (const auto& binding : key_bindings())
            ImGui::Text("%-8s %s", std::string(binding.key).c_str(),
                        std::string(binding.description).c_str());
    }
    ImGui::PopItemWidth();
    ImGui::EndChild();
    state.active_section_changed = false;

    const float chart_top = ImGui::GetCursorPosY();
    ImGui::Separator();
    timing_chart(*state.renderer);
    state.timings_height = ImGui::GetCursorPosY() - chart_top;
    ImGui::PopItemWidth();
    ImGui::End();
}

float scene_size(const Scene& scene) {
    return std::max(glm::length(scene.bounds.max - scene.bounds.min), 1e-3f);
}

std::string_view section_of_view(DebugView view) {
    const std::string_view name = to_string(view);
    for (std::string_view prefix : {"ao", "radiosity", "reflection"})
        if (name.substr(0, prefix.size()) == prefix) return prefix;
    return "frame";
}

std::string_view section_of_setting(std::string_view name) {
    if (const NumericSetting* setting = find_numeric_setting(name)) return setting->group;
    if (name.substr(0, 6) == "light-") return "light";
    if (name == "ao-method") return "ao";
    if (name == "radiosity-method") return "radiosity";
    return "frame";  // generator, view
}

std::string_view section_of_action(KeyAction action, const RenderSettings& after) {
    switch (action) {
        case KeyAction::next_view:
        case KeyAction::previous_view:
            return section_of_view(after.view);
        case KeyAction::next_ao_method:
        case KeyAction::ao_radius_down:
        case KeyAction::ao_radius_up:
        case KeyAction::toggle_layers:
            return "ao";
        case KeyAction::radiosity_radius_down:
        case KeyAction::radiosity_radius_up:
        case KeyAction::toggle_temporal:
            return "radiosity";
        case KeyAction::reset_camera:
            return "camera";
        default:
            return "frame";
    }
}

void set_active_section(WindowState& state, std::string_view section) {
    if (state.active_section == section) return;
    state.active_section = std::string(section);
    state.active_section_changed = true;
}

}  // namespace deepgi
