// Headless OpenGL 4.5 core contexts (ARCHITECTURE.md §6). Three backends:
// - EGL device (EGL_EXT_platform_device): a real GPU, e.g. NVIDIA, with no display server;
// - EGL surfaceless (EGL_MESA_platform_surfaceless): Mesa, llvmpipe on CPU-only machines;
// - OSMesa: Mesa's off-screen library, the fallback when EGL is missing or broken.
// Nothing is ever drawn to a window: every pass renders into a Framebuffer.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace hexlod::render {

enum class GlBackend { Auto, EglDevice, EglSurfaceless, OSMesa };

const char* glBackendName(GlBackend backend); // "auto", "egl-device", "egl-surfaceless", "osmesa"
// Parses a backend name as glBackendName writes it; false for anything else.
bool parseGlBackend(std::string_view name, GlBackend& out);

struct GlContextOptions {
    // Auto tries EGL device (hardware devices only), then EGL surfaceless, then OSMesa. The
    // environment variable HEXLOD_GL_BACKEND, when set, overrides Auto (never an explicit choice).
    GlBackend backend = GlBackend::Auto;
    bool debugOutput = true; // a debug context, its messages sent to the log
};

struct GlContextInfo {
    GlBackend backend = GlBackend::Auto;
    std::string vendor, renderer, version;
    bool software = false;          // llvmpipe, softpipe or another CPU rasteriser
    bool timerQueriesCount = false; // GL_TIMESTAMP advances
    // Whether GL timestamps time the GPU's work. llvmpipe's advance, but they are taken as
    // commands are queued, before its threads rasterise them: a pass there reads far less
    // than it costs.
    bool gpuTimestamps() const { return timerQueriesCount && !software; }
};

class GlContext {
public:
    virtual ~GlContext() = default;
    // Binds the context to the calling thread (creation already did, on the creating thread).
    virtual void makeCurrent() = 0;
    const GlContextInfo& info() const { return info_; }

protected:
    GlContextInfo info_;
};

struct GlContextResult {
    std::unique_ptr<GlContext> context;
    // When context is null: one line per backend tried, "egl-surfaceless: eglInitialize
    // failed (EGL_NOT_INITIALIZED)", so the user sees what was tried and why each failed.
    std::vector<std::string> attempts;
    std::string error() const; // the attempts joined into one message
};

// Creates a context, makes it current on the calling thread and loads the GL functions.
// Requires OpenGL 4.5 core and the functions hexlod uses; a backend without them fails.
GlContextResult createGlContext(const GlContextOptions& options = {});

} // namespace hexlod::render
