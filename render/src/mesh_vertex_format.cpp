#include "hexlod/render/mesh_vertex_format.h"
#include "hexlod/render/gl_api.h"
#include "hexlod/render/gpu_types.h"
#include "hexlod/render/terminal_mesh.h"

#include <cstddef>

namespace hexlod::render {

void setVertexAttributes(uint32_t vao, uint32_t binding, std::span<const VertexAttribute> attributes) {
    for (const VertexAttribute& a : attributes) {
        gl::glEnableVertexArrayAttrib(vao, a.location);
        gl::glVertexArrayAttribFormat(vao, a.location, a.components, a.type, a.normalized, a.offset);
        gl::glVertexArrayAttribBinding(vao, a.location, binding);
    }
}

void setMeshVertexFormat(uint32_t vao, uint32_t binding) {
    const VertexAttribute attributes[] = {
        {HEXLOD_ATTRIBUTE_POSITION, 3, GL_FLOAT, false, offsetof(MeshVertex, position)},
        {HEXLOD_ATTRIBUTE_NORMAL, 3, GL_FLOAT, false, offsetof(MeshVertex, normal)},
        {HEXLOD_ATTRIBUTE_UV, 2, GL_FLOAT, false, offsetof(MeshVertex, uv)},
        {HEXLOD_ATTRIBUTE_COLOR, 4, GL_UNSIGNED_BYTE, true, offsetof(MeshVertex, rgba)},
    };
    setVertexAttributes(vao, binding, attributes);
}

} // namespace hexlod::render
