#include "hexlod/render/mesh_vertex_format.h"
#include "hexlod/render/gl_api.h"
#include "hexlod/render/gpu_types.h"
#include "hexlod/render/terminal_mesh.h"

#include <cstddef>

namespace hexlod::render {

void setMeshVertexFormat(uint32_t vao, uint32_t binding) {
    const struct {
        GLuint location;
        GLint components;
        GLenum type;
        GLboolean normalized;
        GLuint offset;
    } attributes[] = {
        {HEXLOD_ATTRIBUTE_POSITION, 3, GL_FLOAT, GL_FALSE, offsetof(MeshVertex, position)},
        {HEXLOD_ATTRIBUTE_NORMAL, 3, GL_FLOAT, GL_FALSE, offsetof(MeshVertex, normal)},
        {HEXLOD_ATTRIBUTE_UV, 2, GL_FLOAT, GL_FALSE, offsetof(MeshVertex, uv)},
        {HEXLOD_ATTRIBUTE_COLOR, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(MeshVertex, rgba)},
    };
    for (const auto& a : attributes) {
        gl::glEnableVertexArrayAttrib(vao, a.location);
        gl::glVertexArrayAttribFormat(vao, a.location, a.components, a.type, a.normalized, a.offset);
        gl::glVertexArrayAttribBinding(vao, a.location, binding);
    }
}

} // namespace hexlod::render
