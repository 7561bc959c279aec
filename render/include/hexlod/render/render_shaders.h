// The render module's embedded GLSL sources (render/shaders/), generated at build time.
#pragma once

#include "hexlod/render/shader_library.h"

#include <span>

std::span<const hexlod::render::ShaderFile> hexlodRenderShaders();

namespace hexlod::render {

// A library holding the render module's shaders, the base other modules add theirs to.
ShaderLibrary renderShaderLibrary();

} // namespace hexlod::render
