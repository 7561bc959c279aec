// KHR_debug messages to spdlog.
#include "hexlod/render/gl_debug.h"
#include "hexlod/render/gl_api.h"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <string_view>

namespace hexlod::render {
namespace {

std::atomic<uint64_t> errorCount{0};

// Standard error, never spdlog's default standard output: `walk --json` and the other
// commands print their results there, and a driver's warning mid-run must not break them.
spdlog::logger& glLog() {
    static const std::shared_ptr<spdlog::logger> logger = spdlog::stderr_color_mt("gl");
    return *logger;
}

const char* sourceName(GLenum source) {
    switch (source) {
    case GL_DEBUG_SOURCE_API:
        return "api";
    case GL_DEBUG_SOURCE_SHADER_COMPILER:
        return "shader compiler";
    case GL_DEBUG_SOURCE_WINDOW_SYSTEM:
        return "window system";
    case GL_DEBUG_SOURCE_THIRD_PARTY:
        return "third party";
    case GL_DEBUG_SOURCE_APPLICATION:
        return "application";
    default:
        return "other";
    }
}

void APIENTRY onMessage(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                        const GLchar* message, const void*) {
    std::string_view text(message, length >= 0 ? size_t(length) : std::char_traits<char>::length(message));
    // Compile errors already reach the caller through ShaderProgram::build, mapped to file:line;
    // repeating them here as GL errors would only say it twice.
    if (source == GL_DEBUG_SOURCE_SHADER_COMPILER) {
        glLog().debug("GL {} {}: {}", sourceName(source), id, text);
        return;
    }
    if (type == GL_DEBUG_TYPE_ERROR) ++errorCount;
    spdlog::level::level_enum level = spdlog::level::info;
    if (severity == GL_DEBUG_SEVERITY_HIGH || type == GL_DEBUG_TYPE_ERROR)
        level = spdlog::level::err;
    else if (severity == GL_DEBUG_SEVERITY_MEDIUM)
        level = spdlog::level::warn;
    glLog().log(level, "GL {} {}: {}", sourceName(source), id, text);
}

} // namespace

void installGlDebugOutput() {
    gl::glEnable(GL_DEBUG_OUTPUT);
    // Synchronous, so a message names the call that caused it in a debugger's backtrace.
    gl::glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    gl::glDebugMessageCallback(onMessage, nullptr);
    gl::glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DEBUG_SEVERITY_NOTIFICATION, 0, nullptr,
                              GL_FALSE);
}

uint64_t glDebugErrorCount() {
    return errorCount.load();
}

} // namespace hexlod::render
