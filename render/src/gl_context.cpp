// Backend choice and the checks every new context passes (version, functions, debug output).
#include "hexlod/render/gl_context.h"
#include "hexlod/render/gl_api.h"
#include "hexlod/render/gl_debug.h"

#include "gl_backends.h"

#include <cstdlib>
#include <cstring>

namespace hexlod::render {

const char* glBackendName(GlBackend backend) {
    switch (backend) {
    case GlBackend::Auto:
        return "auto";
    case GlBackend::EglDevice:
        return "egl-device";
    case GlBackend::EglSurfaceless:
        return "egl-surfaceless";
    case GlBackend::OSMesa:
        return "osmesa";
    }
    return "?";
}

bool parseGlBackend(std::string_view name, GlBackend& out) {
    for (GlBackend backend :
         {GlBackend::Auto, GlBackend::EglDevice, GlBackend::EglSurfaceless, GlBackend::OSMesa}) {
        if (name == glBackendName(backend)) {
            out = backend;
            return true;
        }
    }
    return false;
}

std::string GlContextResult::error() const {
    std::string message = "no OpenGL 4.5 core context could be created";
    for (const std::string& attempt : attempts) message += "\n  " + attempt;
    return message;
}

bool finishContext(GlBackend backend, bool debug, void (*(*load)(const char*))(), GlContextInfo& info,
                   std::string& why) {
    std::vector<std::string> missing = gl::loadFunctions(load);
    if (!missing.empty()) {
        why = "missing " + std::to_string(missing.size()) + " OpenGL function(s), first " + missing.front();
        return false;
    }
    GLint major = 0, minor = 0, profile = 0;
    gl::glGetIntegerv(GL_MAJOR_VERSION, &major);
    gl::glGetIntegerv(GL_MINOR_VERSION, &minor);
    gl::glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    auto text = [](GLenum name) {
        const GLubyte* value = gl::glGetString(name);
        return value ? std::string(reinterpret_cast<const char*>(value)) : std::string();
    };
    info.backend = backend;
    info.vendor = text(GL_VENDOR);
    info.renderer = text(GL_RENDERER);
    info.version = text(GL_VERSION);
    if (major * 10 + minor < 45 || !(profile & GL_CONTEXT_CORE_PROFILE_BIT)) {
        why = "got OpenGL " + info.version + " (" + info.renderer + "), need 4.5 core";
        return false;
    }
    for (const char* name : {"llvmpipe", "softpipe", "SWR", "Software Rasterizer"}) {
        if (info.renderer.find(name) != std::string::npos) info.software = true;
    }
    // Whether GL_TIMESTAMP advances at all; GlContextInfo::gpuTimestamps says whether it
    // also times the GPU's work.
    GLuint queries[2];
    gl::glCreateQueries(GL_TIMESTAMP, 2, queries);
    gl::glQueryCounter(queries[0], GL_TIMESTAMP);
    gl::glFinish();
    gl::glQueryCounter(queries[1], GL_TIMESTAMP);
    GLuint64 stamps[2] = {0, 0};
    gl::glGetQueryObjectui64v(queries[0], GL_QUERY_RESULT, &stamps[0]);
    gl::glGetQueryObjectui64v(queries[1], GL_QUERY_RESULT, &stamps[1]);
    gl::glDeleteQueries(2, queries);
    info.timerQueriesCount = stamps[0] != 0 || stamps[1] != 0;
    if (debug) installGlDebugOutput();
    while (gl::glGetError() != GL_NO_ERROR) {}
    return true;
}

GlContextResult createGlContext(const GlContextOptions& options) {
    GlBackend requested = options.backend;
    GlContextResult result;
    if (requested == GlBackend::Auto) {
        if (const char* env = std::getenv("HEXLOD_GL_BACKEND"); env && *env) {
            if (!parseGlBackend(env, requested)) {
                result.attempts.push_back(std::string("HEXLOD_GL_BACKEND=") + env +
                                          ": unknown backend (auto, egl-device, egl-surfaceless, osmesa)");
                return result;
            }
        }
    }
    std::vector<GlBackend> order;
    if (requested == GlBackend::Auto)
        order = {GlBackend::EglDevice, GlBackend::EglSurfaceless, GlBackend::OSMesa};
    else
        order = {requested};
    for (GlBackend backend : order) {
        std::string why;
        std::unique_ptr<GlContext> context;
        if (backend == GlBackend::OSMesa)
            context = createOsMesaContext(options.debugOutput, why);
        else {
            // Under Auto the device platform is for real GPUs; Mesa's software device is the
            // same llvmpipe the surfaceless platform gives.
            bool hardwareOnly = requested == GlBackend::Auto;
            context = createEglContext(backend, options.debugOutput, hardwareOnly, why);
        }
        if (context) {
            result.context = std::move(context);
            return result;
        }
        result.attempts.push_back(std::string(glBackendName(backend)) + ": " + why);
    }
    return result;
}

} // namespace hexlod::render
