// Definitions and loader of the function pointers declared in gl_api.h.
#include "hexlod/render/gl_api.h"

namespace hexlod::gl {

#define HEXLOD_GL(type, name) type name = nullptr;
#include "hexlod/render/gl_functions.inc"
#undef HEXLOD_GL

std::vector<std::string> loadFunctions(ProcLoader load) {
    std::vector<std::string> missing;
#define HEXLOD_GL(type, name)                                                                                \
    name = reinterpret_cast<type>(load(#name));                                                              \
    if (!name) missing.emplace_back(#name);
#include "hexlod/render/gl_functions.inc"
#undef HEXLOD_GL
    return missing;
}

} // namespace hexlod::gl
