#include "deepgi/context.hpp"

#include "deepgi/errors.hpp"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <fmt/format.h>

#include <string>
#include <vector>

namespace deepgi {

namespace {

bool has_client_extension(const char* name) {
    const char* extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (extensions == nullptr) return false;
    std::string list = std::string(" ") + extensions + " ";
    return list.find(std::string(" ") + name + " ") != std::string::npos;
}

bool try_initialize(EGLDisplay display) {
    if (display == EGL_NO_DISPLAY) return false;
    EGLint major = 0;
    EGLint minor = 0;
    return eglInitialize(display, &major, &minor) == EGL_TRUE;
}

// Mesa offers a display with no window system at all; NVIDIA's driver offers
// one per GPU device instead.
EGLDisplay open_display() {
    if (has_client_extension("EGL_MESA_platform_surfaceless")) {
        EGLDisplay display =
            eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (try_initialize(display)) return display;
    }
    if (has_client_extension("EGL_EXT_platform_device") &&
        has_client_extension("EGL_EXT_device_enumeration")) {
        EGLint count = 0;
        eglQueryDevicesEXT(0, nullptr, &count);
        std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
        if (count > 0 && eglQueryDevicesEXT(count, devices.data(), &count)) {
            for (EGLDeviceEXT device : devices) {
                EGLDisplay display =
                    eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
                if (try_initialize(display)) return display;
            }
        }
    }
    EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (try_initialize(display)) return display;
    throw GraphicsError(
        "no EGL display could be initialised (tried surfaceless, device and default)");
}

}  // namespace

HeadlessContext::HeadlessContext() {
    EGLDisplay display = open_display();
    display_ = display;
    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
        eglTerminate(display);
        throw GraphicsError("EGL display does not support desktop OpenGL");
    }
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!epoxy_has_egl_extension(display, "EGL_KHR_no_config_context")) {
        const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                            EGL_PBUFFER_BIT, EGL_NONE};
        EGLint count = 0;
        if (!eglChooseConfig(display, config_attributes, &config, 1, &count) || count == 0) {
            eglTerminate(display);
            throw GraphicsError("no EGL config supports desktop OpenGL");
        }
    }
    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                         4,
                                         EGL_CONTEXT_MINOR_VERSION,
                                         5,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
    if (context == EGL_NO_CONTEXT) {
        eglTerminate(display);
        throw GraphicsError(
            fmt::format("cannot create an OpenGL 4.5 core context through EGL (error 0x{:04x})",
                        eglGetError()));
    }
    context_ = context;
    if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context) != EGL_TRUE) {
        eglDestroyContext(display, context);
        eglTerminate(display);
        throw GraphicsError("cannot make the EGL context current without a surface");
    }
}

HeadlessContext::~HeadlessContext() {
    auto display = static_cast<EGLDisplay>(display_);
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, static_cast<EGLContext>(context_));
    eglTerminate(display);
}

ContextInfo query_context_info() {
    auto text = [](GLenum name) {
        const auto* value = reinterpret_cast<const char*>(glGetString(name));
        return std::string(value != nullptr ? value : "");
    };
    ContextInfo info{text(GL_VENDOR), text(GL_RENDERER), text(GL_VERSION), false};
    for (const char* software : {"llvmpipe", "softpipe", "swrast", "SWR"}) {
        if (info.renderer.find(software) != std::string::npos) info.is_software_renderer = true;
    }
    return info;
}

}  // namespace deepgi
