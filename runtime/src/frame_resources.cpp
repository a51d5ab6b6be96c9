#include "frame_resources.hpp"

#include "deepgi/errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

namespace deepgi {

void FrameResources::publish(const std::string& name, GLuint texture) {
    if (!running_pass_.empty()) {
        if (std::find(declared_writes_->begin(), declared_writes_->end(), name) ==
            declared_writes_->end()) {
            throw GraphicsError(
                fmt::format("pass '{}' writes the texture '{}', which it does not "
                            "declare",
                            running_pass_, name));
        }
        published_.push_back(name);
    }
    textures_[name] = texture;
}

void FrameResources::begin_frame_textures() {
    textures_.clear();
}

void FrameResources::begin_pass(std::string_view pass, const std::vector<std::string>& writes,
                                const std::vector<std::string>& value_reads) {
    running_pass_ = pass;
    declared_writes_ = &writes;
    declared_value_reads_ = &value_reads;
    published_.clear();
}

void FrameResources::end_pass() {
    const std::string pass = std::exchange(running_pass_, {});
    for (const auto& name : *declared_writes_) {
        if (std::find(published_.begin(), published_.end(), name) == published_.end())
            throw GraphicsError(
                fmt::format("pass '{}' declares the texture '{}' but did not "
                            "write it",
                            pass, name));
    }
}

GLuint FrameResources::texture(std::string_view name) const {
    const auto found = textures_.find(name);
    if (found == textures_.end())
        throw GraphicsError(fmt::format("no pass has written the texture '{}' yet", name));
    return found->second;
}

void FrameResources::publish_int(const std::string& name, int value) {
    integers_[name] = value;
}

int FrameResources::integer(std::string_view name) const {
    const auto found = integers_.find(name);
    if (found == integers_.end())
        throw GraphicsError(fmt::format("no pass has published the value '{}' yet", name));
    return found->second;
}

float FrameResources::value(std::string_view name) const {
    if (running_pass_.empty() || declared_value_reads_ == nullptr ||
        std::find(declared_value_reads_->begin(), declared_value_reads_->end(), name) ==
            declared_value_reads_->end()) {
        throw GraphicsError(fmt::format("pass '{}' reads the value '{}', which it does not declare",
                                        running_pass_, name));
    }
    const auto found = values_.find(name);
    if (found == values_.end())
        throw GraphicsError(fmt::format("no enabled pass writes the value '{}'", name));
    return found->second;
}

void FrameResources::allocate_display(int width, int height) {
    display = gl::create_texture_2d(GL_RGBA8, width, height);
    glObjectLabel(GL_TEXTURE, display.get(), -1, "display");
    display_framebuffer = gl::create_framebuffer();
    glNamedFramebufferTexture(display_framebuffer.get(), GL_COLOR_ATTACHMENT0, display.get(), 0);
    gl::check_framebuffer(display_framebuffer, "display");
}

namespace {

void clear_slot(const HistoryPair& pair, GLuint texture) {
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearTexImage(texture, 0, pair.clear_format, GL_FLOAT, zero);
}

}  // namespace

HistoryPair& FrameResources::allocate_history(const std::string& name, GLenum internal_format,
                                              int width, int height) {
    HistoryPair& pair = history_[name];
    // A reallocation for another setting (the shadow map's size, the
    // pyramid's depth) re-creates every pass's targets, but history of the
    // same size and format is still this camera's: kept, with its slot
    // order, so a still camera's running mean goes on. A new size drops
    // history anyway (Renderer::set_settings).
    if (pair.internal_format == internal_format && pair.width == width && pair.height == height)
        return pair;
    pair.internal_format = internal_format;
    pair.width = width;
    pair.height = height;
    pair.clear_format = internal_format == GL_DEPTH_COMPONENT32F ? GL_DEPTH_COMPONENT : GL_RGBA;
    for (int slot = 0; slot < 2; ++slot) {
        pair.slots[slot] = gl::create_texture_2d(internal_format, width, height);
        const std::string label = fmt::format("history {} [{}]", name, slot);
        glObjectLabel(GL_TEXTURE, pair.slots[slot].get(), -1, label.c_str());
        clear_slot(pair, pair.slots[slot].get());
    }
    pair.written_slot = 0;
    return pair;
}

HistoryPair& FrameResources::history(std::string_view name) {
    const auto found = history_.find(name);
    if (found == history_.end())
        throw GraphicsError(fmt::format("no history named '{}' was allocated", name));
    return found->second;
}

void FrameResources::invalidate_history(const std::string& reason) {
    history_valid_ = false;
    for (auto& [name, pair] : history_) clear_slot(pair, pair.previous());
    const std::string message = fmt::format("history invalidated: {}", reason);
    history_log_.push_back(message);
    glDebugMessageInsert(GL_DEBUG_SOURCE_APPLICATION, GL_DEBUG_TYPE_MARKER, 0,
                         GL_DEBUG_SEVERITY_NOTIFICATION, -1, message.c_str());
}

void FrameResources::end_frame() {
    for (auto& [name, pair] : history_) pair.written_slot = 1 - pair.written_slot;
    previous_camera = camera;
    history_valid_ = true;
}

}  // namespace deepgi
