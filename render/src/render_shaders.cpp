// The render module's shader library.
#include "hexlod/render/render_shaders.h"

namespace hexlod::render {

ShaderLibrary renderShaderLibrary() {
    ShaderLibrary library;
    library.add(hexlodRenderShaders());
    return library;
}

} // namespace hexlod::render
