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

// Whether an EGL device is a software rasteriser: Mesa marks its llvmpipe
// device with EGL_MESA_device_software. Without EGL_EXT_device_query the
// device cannot be asked, and counts as hardware.
bool is_software_device(EGLDeviceEXT device) {
    if (!has_client_extension("EGL_EXT_device_query")) return false;
    const char* extensions = eglQueryDeviceStringEXT(device, EGL_EXTENSIONS);
    if (extensions == nullptr) return false;
    return (std::string(" ") + extensions + " ").find(" EGL_MESA_device_software ") !=
           std::string::npos;
}

std::vector<EGLDeviceEXT> query_devices() {
    if (!has_client_extension("EGL_EXT_platform_device") ||
        !has_client_extension("EGL_EXT_device_enumeration"))
        return {};
    EGLint count = 0;
    if (!eglQueryDevicesEXT(0, nullptr, &count) || count <= 0) return {};
    std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
    if (!eglQueryDevicesEXT(count, devices.data(), &count)) return {};
    devices.resize(static_cast<std::size_t>(count));
    return devices;
}

EGLDisplay try_device(EGLDeviceEXT device) {
    EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    return try_initialize(display) ? display : EGL_NO_DISPLAY;
}

// A GPU first: NVIDIA's driver offers one EGL device per GPU, and where it is
// installed beside Mesa (through glvnd) Mesa's surfaceless display would
// otherwise win and render on llvmpipe. Then Mesa's display with no window
// system at all (llvmpipe on a machine without a GPU), then any device,
// then the default display.
EGLDisplay open_display() {
    const std::vector<EGLDeviceEXT> devices = query_devices();
    for (EGLDeviceEXT device : devices) {
        if (is_software_device(device)) continue;
        if (EGLDisplay display = try_device(device); display != EGL_NO_DISPLAY) return display;
    }
    if (has_client_extension("EGL_MESA_platform_surfaceless")) {
        EGLDisplay display =
            eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (try_initialize(display)) return display;
    }
    for (EGLDeviceEXT device : devices) {
        if (EGLDisplay display = try_device(device); display != EGL_NO_DISPLAY) return display;
    }
    EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (try_initialize(display)) return display;
    throw GraphicsError(
        "no EGL display could be initialised (tried GPU devices, surfaceless, software devices "
        "and default)");
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
