// Packing base volumes for the GPU, and their vertex array.
#include "hexlod/lod/volume_vertex.h"
#include "hexlod/render/gl_api.h"
#include "hexlod/render/gpu_types.h"
#include "hexlod/render/mesh_vertex_format.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace hexlod::lod {
namespace {

uint32_t snorm10(float value) {
    const float clamped = std::isnan(value) ? 0.0f : std::clamp(value, -1.0f, 1.0f);
    return uint32_t(int32_t(std::lround(clamped * 511.0f))) & 0x3ffu;
}

// The GL's conversion of a signed normalized 10-bit component (OpenGL 4.5, 2.3.5.1).
float fromSnorm10(uint32_t bits) {
    const int32_t value = int32_t(bits << 22) >> 22; // sign-extend the 10 bits
    return std::max(float(value) / 511.0f, -1.0f);
}

template <typename Element> uint32_t storage(const std::vector<Element>& data) {
    return immutableBuffer(data.data(), data.size() * sizeof(Element));
}

} // namespace

uint32_t immutableBuffer(const void* data, size_t bytes) {
    uint32_t buffer = 0;
    gl::glCreateBuffers(1, &buffer);
    gl::glNamedBufferStorage(buffer, GLsizeiptr(std::max<size_t>(bytes, 4)), bytes ? data : nullptr, 0);
    return buffer;
}

uint32_t packSnorm10(const glm::vec3& unit) {
    return snorm10(unit.x) | (snorm10(unit.y) << 10) | (snorm10(unit.z) << 20);
}

glm::vec3 unpackSnorm10(uint32_t packed) {
    return {fromSnorm10(packed & 0x3ffu), fromSnorm10((packed >> 10) & 0x3ffu),
            fromSnorm10((packed >> 20) & 0x3ffu)};
}

std::vector<VolumeVertex> packVolumeVertices(std::span<const render::MeshVertex> vertices) {
    std::vector<VolumeVertex> packed;
    packed.reserve(vertices.size());
    for (const render::MeshVertex& v : vertices)
        packed.push_back({v.position, packSnorm10(v.normal), v.uv.y > 0.0f ? v.uv.x : -1.0f, v.rgba});
    return packed;
}

VolumeBuffers uploadVolumeMesh(const render::TerminalMesh& mesh) {
    VolumeBuffers out;
    const std::vector<VolumeVertex> vertices = packVolumeVertices(mesh.vertices);
    out.vertexBuffer = storage(vertices);
    if (mesh.vertices.size() <= 0x10000) {
        const std::vector<uint16_t> narrow(mesh.indices.begin(), mesh.indices.end());
        out.indexBuffer = storage(narrow);
        out.indexType = GL_UNSIGNED_SHORT, out.indexSize = 2;
    } else {
        out.indexBuffer = storage(mesh.indices);
        out.indexType = GL_UNSIGNED_INT, out.indexSize = 4;
    }
    out.bytes = vertices.size() * sizeof(VolumeVertex) + mesh.indices.size() * out.indexSize;

    const render::VertexAttribute attributes[] = {
        {HEXLOD_ATTRIBUTE_POSITION, 3, GL_FLOAT, false, offsetof(VolumeVertex, position)},
        {HEXLOD_ATTRIBUTE_NORMAL, 4, GL_INT_2_10_10_10_REV, true, offsetof(VolumeVertex, normal)},
        {HEXLOD_ATTRIBUTE_ELEMENT, 1, GL_FLOAT, false, offsetof(VolumeVertex, element)},
        {HEXLOD_ATTRIBUTE_COLOR, 4, GL_UNSIGNED_BYTE, true, offsetof(VolumeVertex, rgba)},
    };
    gl::glCreateVertexArrays(1, &out.vao);
    render::setVertexAttributes(out.vao, 0, attributes);
    gl::glVertexArrayVertexBuffer(out.vao, 0, out.vertexBuffer, 0, sizeof(VolumeVertex));
    gl::glVertexArrayElementBuffer(out.vao, out.indexBuffer);
    return out;
}

void releaseVolumeMesh(VolumeBuffers& buffers) {
    if (buffers.vao) gl::glDeleteVertexArrays(1, &buffers.vao);
    for (uint32_t buffer : {buffers.vertexBuffer, buffers.indexBuffer})
        if (buffer) gl::glDeleteBuffers(1, &buffer);
    buffers = {};
}

} // namespace hexlod::lod
