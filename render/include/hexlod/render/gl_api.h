// The OpenGL 4.5 core functions hexlod calls, as process-wide function pointers in
// hexlod::gl, loaded from whichever backend made a context current.
//
// Why not libepoxy: epoxy resolves entry points only through GLX or EGL, and aborts when the
// current context is OSMesa's, whose DSA and timer-query functions exist only through
// OSMesaGetProcAddress (libOSMesa does not export them). Loading every pointer from the
// backend's own getProcAddress serves EGL and OSMesa alike. The pointers live in a
// namespace, so they never collide with the gl* symbols libOSMesa exports.
#pragma once

// Types and PFN typedefs only: no prototypes, so every call goes through the pointers below.
#include <GL/glcorearb.h>

#include <string>
#include <vector>

namespace hexlod::gl {

#define HEXLOD_GL(type, name) extern type name;
#include "hexlod/render/gl_functions.inc"
#undef HEXLOD_GL

using ProcLoader = void (*(*)(const char* name))();

// Resolves every function with `load`; returns the names it could not find (empty when all
// were). Call with the new context current, before any GL call.
std::vector<std::string> loadFunctions(ProcLoader load);

} // namespace hexlod::gl
