// EGL contexts without a window system: the device platform (EGL_EXT_platform_device, a GPU
// with no display server) and Mesa's surfaceless platform (llvmpipe on CPU-only machines).
// Both render only into framebuffer objects, so the context is made current with no surface
// (EGL_KHR_surfaceless_context) and no config (EGL_KHR_no_config_context).
#include "gl_backends.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <string_view>

namespace hexlod::render {
namespace {

std::string eglErrorName(EGLint error) {
    switch (error) {
    case EGL_SUCCESS:
        return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
        return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
        return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
        return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
        return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
        return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
        return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
        return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
        return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
        return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
        return "EGL_BAD_SURFACE";
    default:
        return "EGL error " + std::to_string(error);
    }
}

bool hasExtension(const char* list, std::string_view name) {
    if (!list) return false;
    std::string_view all(list);
    for (size_t at = 0; at < all.size();) {
        size_t end = all.find(' ', at);
        if (end == std::string_view::npos) end = all.size();
        if (all.substr(at, end - at) == name) return true;
        at = end + 1;
    }
    return false;
}

// A display, once initialised, stays so for the process: eglGetPlatformDisplay returns the
// same EGLDisplay to every context, and eglTerminate would unload the driver (llvmpipe is
// tens of MB of code and an LLVM instance) for the next context to load again. It would also
// drop the driver's globals, so that LeakSanitizer would report what they held as leaks.
class EglContext final : public GlContext {
public:
    EglContext(EGLDisplay display, EGLContext context) : display_(display), context_(context) {}
    ~EglContext() override {
        if (eglGetCurrentContext() == context_)
            eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display_, context_);
    }
    void makeCurrent() override { eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_); }
    GlContextInfo& mutableInfo() { return info_; }

private:
    EGLDisplay display_;
    EGLContext context_;
};

// The first device that is hardware (or any device, unless hardwareOnly), as a display.
EGLDisplay deviceDisplay(bool hardwareOnly, std::string& why) {
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto queryDeviceString =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!queryDevices || !queryDeviceString || !getPlatformDisplay) {
        why = "EGL_EXT_device_enumeration is not available";
        return EGL_NO_DISPLAY;
    }
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (!queryDevices(16, devices, &count) || count == 0) {
        why = "no EGL device found";
        return EGL_NO_DISPLAY;
    }
    int software = 0;
    for (EGLint i = 0; i < count; ++i) {
        if (hasExtension(queryDeviceString(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software")) {
            ++software;
            if (hardwareOnly) continue;
        }
        EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (display != EGL_NO_DISPLAY) return display;
    }
    why = std::to_string(count) + " EGL device(s), " + std::to_string(software) +
          " of them Mesa's software device, none usable" + (hardwareOnly ? " as hardware" : "");
    return EGL_NO_DISPLAY;
}

EGLDisplay surfacelessDisplay(std::string& why) {
    if (!hasExtension(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), "EGL_MESA_platform_surfaceless")) {
        why = "EGL_MESA_platform_surfaceless is not available (not Mesa's libEGL?)";
        return EGL_NO_DISPLAY;
    }
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    EGLDisplay display = getPlatformDisplay
                             ? getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr)
                             : EGL_NO_DISPLAY;
    if (display == EGL_NO_DISPLAY)
        why = "eglGetPlatformDisplayEXT failed (" + eglErrorName(eglGetError()) + ")";
    return display;
}

} // namespace

std::unique_ptr<GlContext> createEglContext(GlBackend backend, bool debug, bool hardwareOnly,
                                            std::string& why) {
    if (eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS) == nullptr && eglGetError() != EGL_SUCCESS) {
        why = "libEGL reports no client extensions";
        return nullptr;
    }
    EGLDisplay display =
        backend == GlBackend::EglDevice ? deviceDisplay(hardwareOnly, why) : surfacelessDisplay(why);
    if (display == EGL_NO_DISPLAY) return nullptr;
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
        why = "eglInitialize failed (" + eglErrorName(eglGetError()) + ")";
        return nullptr;
    }
    const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
    for (const char* needed :
         {"EGL_KHR_create_context", "EGL_KHR_surfaceless_context", "EGL_KHR_no_config_context"}) {
        if (!hasExtension(extensions, needed)) {
            why = std::string(needed) + " is not supported by " +
                  (eglQueryString(display, EGL_VENDOR) ?: "EGL");
            return nullptr;
        }
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        why = "eglBindAPI(EGL_OPENGL_API) failed (" + eglErrorName(eglGetError()) + ")";
        return nullptr;
    }
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                 4,
                                 EGL_CONTEXT_MINOR_VERSION,
                                 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                 EGL_CONTEXT_OPENGL_DEBUG,
                                 debug ? EGL_TRUE : EGL_FALSE,
                                 EGL_NONE};
    EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (context == EGL_NO_CONTEXT) {
        why = "eglCreateContext for OpenGL 4.5 core failed (" + eglErrorName(eglGetError()) + ")";
        return nullptr;
    }
    auto result = std::make_unique<EglContext>(display, context);
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        why = "eglMakeCurrent failed (" + eglErrorName(eglGetError()) + ")";
        return nullptr;
    }
    if (!finishContext(backend, debug, eglGetProcAddress, result->mutableInfo(), why)) return nullptr;
    return result;
}

} // namespace hexlod::render
