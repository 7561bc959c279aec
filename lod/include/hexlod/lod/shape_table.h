// Every terminal shape of a scene on the GPU, under one global index (shapeBase of its grammar
// + its shape id): the meshes of the mesh library in one vertex and one index buffer, as
// ShapeGeometry (normals in unit scope space, double-sided surfaces as one triangle with two
// colours), and per shape what the draw passes need (nominal size, mesh bounds, impostor
// layer, whether it draws without face culling).
#pragma once

#include "hexlod/lod/gpu_cull.h"
#include "hexlod/lod/shape_geometry.h"
#include "hexlod/render/terminal_mesh_library.h"

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace hexlod::lod {

// Per global shape, as the draw passes read it (std430, three vec4).
struct GpuShape {
    glm::vec4 nominalSize; // xyz: (W, H, D) the normals are metric at; w: impostor layer, -1 none
    glm::vec4 boundsMin;   // unit scope space
    glm::vec4 boundsMax;
};

// A coarser mesh that LOD4 terminals of a shape draw where it is small on screen (meshShape in
// cull_shared.h); the table gives it a global shape of its own, after every grammar's.
struct CoarseMesh {
    uint32_t shape = 0; // the global shape it serves
    std::shared_ptr<const render::TerminalMesh> mesh;
    glm::vec3 deviation{0.0f}; // meshDeviation between the shape's mesh and this one
};

// Consecutive global shapes that draw alike: two-sided ones (ShapeGeometry::twoSided) without
// face culling, the others with back faces culled.
struct SidedRun {
    uint32_t first = 0, count = 0;
    bool twoSided = false;
};

class ShapeTable {
public:
    ShapeTable() = default;
    ~ShapeTable();
    ShapeTable(const ShapeTable&) = delete;
    ShapeTable& operator=(const ShapeTable&) = delete;

    // Uploads every mesh of `library` (grammars in the scene's order) and of `coarse` once.
    void upload(const render::TerminalMeshLibrary& library, std::span<const CoarseMesh> coarse = {});
    // Records which impostor layer serves a global shape (-1: none, it always draws at LOD4).
    void setImpostorLayer(uint32_t shape, int layer);
    // Sends the per-shape table to the GPU; call after the layers are set.
    void commit();

    uint32_t shapeCount() const { return uint32_t(shapes_.size()); }
    // The grammars' shapes come first; the coarse ones (CoarseMesh) from here on.
    uint32_t firstCoarseShape() const { return firstCoarse_; }
    uint32_t shapeBase(uint32_t grammar) const { return bases_.at(grammar); }
    const std::vector<MeshDrawInfo>& meshes() const { return draws_; }
    const std::vector<GpuShape>& shapes() const { return shapes_; }
    std::vector<uint8_t> impostorFlags() const;
    // Per global shape, its coarse mesh as the cull pass reads it (CullInputs::shapeCoarse).
    const std::vector<glm::vec4>& coarseTable() const { return coarse_; }
    uint32_t triangles(uint32_t shape) const { return draws_.at(shape).indexCount / 3; }

    const std::vector<SidedRun>& sidedRuns() const { return sidedRuns_; }

    // Binds the meshes to `vao` as ShapeVertex attributes from vertex buffer binding `binding`,
    // and the index buffer.
    void bindVertices(uint32_t vao, uint32_t binding) const;
    uint32_t vertexBuffer() const { return vertices_; }
    uint32_t shapeBuffer() const { return table_; }
    uint64_t byteSize() const { return bytes_; }

private:
    std::vector<uint32_t> bases_;
    std::vector<MeshDrawInfo> draws_;
    std::vector<GpuShape> shapes_;
    std::vector<glm::vec4> coarse_;
    std::vector<SidedRun> sidedRuns_;
    uint32_t firstCoarse_ = 0;
    uint32_t vertices_ = 0, indices_ = 0, table_ = 0;
    uint64_t bytes_ = 0;
};

} // namespace hexlod::lod
