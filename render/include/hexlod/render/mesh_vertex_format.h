// MeshVertex (terminal_mesh.h) as GL vertex attributes, at the locations gpu_types.h names:
// the impostor baker's meshes and the ground. The LOD4 pass and the base volumes upload
// packed layouts of their own (lod/shape_geometry.h, lod/volume_vertex.h).
#pragma once

#include <cstdint>

namespace hexlod::render {

// Enables position, normal, uv and colour on `vao`, read from vertex buffer binding `binding`
// (the buffer itself is bound by the caller with glVertexArrayVertexBuffer).
void setMeshVertexFormat(uint32_t vao, uint32_t binding);

} // namespace hexlod::render
