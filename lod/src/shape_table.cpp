// One vertex and index buffer for all terminal meshes, each distinct mesh uploaded once.
#include "hexlod/lod/shape_table.h"
#include "hexlod/render/gl_api.h"

#include <map>

namespace hexlod::lod {

ShapeTable::~ShapeTable() {
    for (uint32_t buffer : {vertices_, indices_, table_})
        if (buffer) gl::glDeleteBuffers(1, &buffer);
}

void ShapeTable::upload(const render::TerminalMeshLibrary& library, std::span<const CoarseMesh> coarse) {
    std::vector<render::MeshVertex> vertices;
    std::vector<uint32_t> indices;
    std::map<const render::TerminalMesh*, MeshDrawInfo> placed;
    const auto add = [&](const render::TerminalMesh& mesh) {
        auto [it, inserted] = placed.try_emplace(&mesh);
        if (inserted) {
            it->second = {uint32_t(mesh.indices.size()), uint32_t(indices.size()), int32_t(vertices.size())};
            // Normals in unit scope space: the LOD4 vertex shader carries them to a terminal's
            // scope with one division, where a stored normal would need the shape's nominal
            // size, a buffer read per vertex (terminal_mesh.vert).
            for (render::MeshVertex v : mesh.vertices) {
                v.normal = render::unitSpaceNormal(v.normal, mesh.nominalSize);
                vertices.push_back(v);
            }
            indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
        }
        draws_.push_back(it->second);
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
                             GLsizeiptr(std::max<size_t>(vertices.size(), 1) * sizeof(render::MeshVertex)),
                             vertices.empty() ? nullptr : vertices.data(), 0);
    gl::glCreateBuffers(1, &indices_);
    gl::glNamedBufferStorage(indices_, GLsizeiptr(std::max<size_t>(indices.size(), 1) * sizeof(uint32_t)),
                             indices.empty() ? nullptr : indices.data(), 0);
    bytes_ = vertices.size() * sizeof(render::MeshVertex) + indices.size() * sizeof(uint32_t);
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
