// One vertex and index buffer for all terminal meshes, each distinct mesh uploaded once.
#include "hexlod/lod/shape_table.h"
#include "hexlod/render/gl_api.h"
#include "hexlod/render/gpu_types.h"
#include "hexlod/render/mesh_vertex_format.h"

#include <cstddef>
#include <map>

namespace hexlod::lod {

ShapeTable::~ShapeTable() {
    for (uint32_t buffer : {vertices_, indices_, table_})
        if (buffer) gl::glDeleteBuffers(1, &buffer);
}

void ShapeTable::upload(const render::TerminalMeshLibrary& library, std::span<const CoarseMesh> coarse) {
    std::vector<ShapeVertex> vertices;
    std::vector<uint32_t> indices;
    std::map<const render::TerminalMesh*, std::pair<MeshDrawInfo, bool>> placed; // and two-sided
    const auto add = [&](const render::TerminalMesh& mesh) {
        auto [it, inserted] = placed.try_emplace(&mesh);
        if (inserted) {
            const ShapeGeometry geometry = shapeGeometry(mesh);
            it->second = {
                {uint32_t(geometry.indices.size()), uint32_t(indices.size()), int32_t(vertices.size())},
                geometry.twoSided};
            vertices.insert(vertices.end(), geometry.vertices.begin(), geometry.vertices.end());
            indices.insert(indices.end(), geometry.indices.begin(), geometry.indices.end());
        }
        const auto& [draw, twoSided] = it->second;
        if (sidedRuns_.empty() || sidedRuns_.back().twoSided != twoSided)
            sidedRuns_.push_back({uint32_t(draws_.size()), 0, twoSided});
        ++sidedRuns_.back().count;
        draws_.push_back(draw);
        shapes_.push_back({glm::vec4(mesh.nominalSize, -1.0f), glm::vec4(mesh.boundsMin, 0.0f),
                           glm::vec4(mesh.boundsMax, 0.0f)});
    };
    for (uint32_t g = 0; g < library.grammarCount(); ++g) {
        bases_.push_back(uint32_t(draws_.size()));
        for (uint16_t s = 0; s < library.shapeCount(g); ++s) add(library.mesh(g, s));
    }
    firstCoarse_ = uint32_t(draws_.size());
    coarse_.assign(draws_.size() + coarse.size(), glm::vec4(0.0f, 0.0f, 0.0f, -1.0f));
    for (const CoarseMesh& variant : coarse) {
        coarse_.at(variant.shape) = glm::vec4(variant.deviation, float(draws_.size()));
        add(*variant.mesh);
    }
    gl::glCreateBuffers(1, &vertices_);
    gl::glNamedBufferStorage(vertices_,
                             GLsizeiptr(std::max<size_t>(vertices.size(), 1) * sizeof(ShapeVertex)),
                             vertices.empty() ? nullptr : vertices.data(), 0);
    gl::glCreateBuffers(1, &indices_);
    gl::glNamedBufferStorage(indices_, GLsizeiptr(std::max<size_t>(indices.size(), 1) * sizeof(uint32_t)),
                             indices.empty() ? nullptr : indices.data(), 0);
    bytes_ = vertices.size() * sizeof(ShapeVertex) + indices.size() * sizeof(uint32_t);
}

void ShapeTable::bindVertices(uint32_t vao, uint32_t binding) const {
    const render::VertexAttribute attributes[] = {
        {HEXLOD_ATTRIBUTE_POSITION, 3, GL_FLOAT, false, offsetof(ShapeVertex, position)},
        {HEXLOD_ATTRIBUTE_NORMAL, 3, GL_FLOAT, false, offsetof(ShapeVertex, normal)},
        {HEXLOD_ATTRIBUTE_COLOR, 4, GL_UNSIGNED_BYTE, true, offsetof(ShapeVertex, rgba)},
        {HEXLOD_ATTRIBUTE_BACK_COLOR, 4, GL_UNSIGNED_BYTE, true, offsetof(ShapeVertex, backRgba)},
    };
    render::setVertexAttributes(vao, binding, attributes);
    gl::glVertexArrayVertexBuffer(vao, binding, vertices_, 0, sizeof(ShapeVertex));
    gl::glVertexArrayElementBuffer(vao, indices_);
}

void ShapeTable::setImpostorLayer(uint32_t shape, int layer) {
    shapes_.at(shape).nominalSize.w = float(layer);
}

void ShapeTable::commit() {
    if (table_) gl::glDeleteBuffers(1, &table_);
    gl::glCreateBuffers(1, &table_);
    gl::glNamedBufferStorage(table_, GLsizeiptr(std::max<size_t>(shapes_.size(), 1) * sizeof(GpuShape)),
                             shapes_.empty() ? nullptr : shapes_.data(), 0);
}

std::vector<uint8_t> ShapeTable::impostorFlags() const {
    std::vector<uint8_t> flags(shapes_.size());
    for (size_t s = 0; s < shapes_.size(); ++s) flags[s] = shapes_[s].nominalSize.w >= 0.0f;
    return flags;
}

} // namespace hexlod::lod
