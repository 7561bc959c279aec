// The backends behind createGlContext: each creates a 4.5 core context, makes it current
// and loads the GL functions, or returns null and says why in `why`.
#pragma once

#include "hexlod/render/gl_context.h"

#include <memory>
#include <string>

namespace hexlod::render {

// `backend` is EglDevice or EglSurfaceless. For EglDevice, `hardwareOnly` skips Mesa's
// software device (Auto leaves that to the surfaceless platform).
std::unique_ptr<GlContext> createEglContext(GlBackend backend, bool debug, bool hardwareOnly,
                                            std::string& why);
std::unique_ptr<GlContext> createOsMesaContext(bool debug, std::string& why);

// With the context current: loads the functions through `load` and fills `info` (strings,
// software rasteriser, whether timer queries count). False, with `why`, when the context is
// not 4.5 core or lacks a function.
bool finishContext(GlBackend backend, bool debug, void (*(*load)(const char*))(), GlContextInfo& info,
                   std::string& why);

} // namespace hexlod::render
