#pragma once
// OpenGL 4.5 core contexts: EGL without any window system (headless, CI, GPU
// servers) and a GLFW window (interactive, or hidden for the xvfb test).
#include <memory>
#include <string>

struct GLFWwindow;

namespace deepgi {

struct ContextInfo {
    std::string vendor;
    std::string renderer;
    std::string version;
    // llvmpipe/softpipe run GL on the CPU, where timer queries say nothing useful.
    bool is_software_renderer = false;
};

ContextInfo query_context_info();

// EGL: Mesa's surfaceless platform first, then an EGL device (NVIDIA), then the
// default display. The context is current on the calling thread while alive.
class HeadlessContext {
public:
    HeadlessContext();
    ~HeadlessContext();
    HeadlessContext(const HeadlessContext&) = delete;
    HeadlessContext& operator=(const HeadlessContext&) = delete;

private:
    void* display_ = nullptr;
    void* context_ = nullptr;
};

// A GLFW window with a 4.5 core context, current on the calling thread.
class WindowContext {
public:
    WindowContext(int width, int height, const std::string& title, bool visible);
    ~WindowContext();
    WindowContext(const WindowContext&) = delete;
    WindowContext& operator=(const WindowContext&) = delete;
    GLFWwindow* window() const { return window_; }

private:
    GLFWwindow* window_ = nullptr;
};

}  // namespace deepgi
