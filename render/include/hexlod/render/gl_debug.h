// GL debug output (KHR_debug) into the log, and a count of the errors it reported, so tests
// can assert that a pass raised none.
#pragma once

#include <cstdint>

namespace hexlod::render {

// Sends the current context's debug messages to spdlog: high severity as errors, medium as
// warnings, low as info; notifications are muted, and shader compiler messages go to the debug
// level (ShaderProgram::build reports them). createGlContext calls it.
void installGlDebugOutput();

// Errors (GL_DEBUG_TYPE_ERROR) reported by debug output since the process started.
uint64_t glDebugErrorCount();

} // namespace hexlod::render
