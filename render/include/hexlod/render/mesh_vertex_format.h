// MeshVertex (terminal_mesh.h) as GL vertex attributes: every pass that draws meshes binds
// them through here, at the locations gpu_types.h names.
#pragma once

#include <cstdint>

namespace hexlod::render {

// Enables position, normal, uv and colour on `vao`, read from vertex buffer binding `binding`
// (the buffer itself is bound by the caller with glVertexArrayVertexBuffer).
void setMeshVertexFormat(uint32_t vao, uint32_t binding);

} // namespace hexlod::render
