#include "deepgi/context.hpp"

#include "deepgi/errors.hpp"

#include <GLFW/glfw3.h>
#include <fmt/format.h>

namespace deepgi {

WindowContext::WindowContext(int width, int height, const std::string& title, bool visible) {
    if (glfwInit() != GLFW_TRUE)
        throw NoDisplayError("cannot open a window: GLFW found no display");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (window_ == nullptr) {
        glfwTerminate();
        throw GraphicsError("cannot create a GLFW window with an OpenGL 4.5 core context");
    }
    glfwMakeContextCurrent(window_);
}

WindowContext::~WindowContext() {
    glfwDestroyWindow(window_);
    glfwTerminate();
}

}  // namespace deepgi
