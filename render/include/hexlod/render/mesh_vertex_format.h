// Vertex layouts as GL vertex attributes, at the locations gpu_types.h names: every layout
// binds through setVertexAttributes. MeshVertex (terminal_mesh.h) is the impostor baker's and
// the ground's; the LOD4 pass and the base volumes upload packed layouts of their own
// (lod/shape_geometry.h, lod/volume_vertex.h), and LOD4's instances come from draw lists.
#pragma once

#include <cstdint>
#include <span>

namespace hexlod::render {

// One attribute of a vertex layout: glVertexArrayAttribFormat's arguments.
struct VertexAttribute {
    uint32_t location;
    int32_t components;
    uint32_t type; // GL_FLOAT, GL_UNSIGNED_BYTE, ...
    bool normalized;
    uint32_t offset;
};

// Enables each of `attributes` on `vao`, read from vertex buffer binding `binding`.
void setVertexAttributes(uint32_t vao, uint32_t binding, std::span<const VertexAttribute> attributes);

// Enables position, normal, uv and colour on `vao`, read from vertex buffer binding `binding`
// (the buffer itself is bound by the caller with glVertexArrayVertexBuffer).
void setMeshVertexFormat(uint32_t vao, uint32_t binding);

} // namespace hexlod::render
