// Base volumes on the GPU (LOD0, and the shells under LOD2-4 terminals): per batch, the
// extruded set's buildings as one mesh in cell-local metres, built on first use and kept
// within a byte budget, least recently drawn first out; the meshes of the last frame stay
// whatever the budget.
#pragma once

#include "hexlod/cells/batch_catalog.h"
#include "hexlod/lod/volume_vertex.h"
#include "hexlod/render/base_volume_mesh.h"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace hexlod::lod {

struct VolumeMesh {
    VolumeBuffers gpu; // the vertex array and buffers (volume_vertex.h)
    uint32_t indexCount = 0;
    // LOD1's view of the same batch (walls at inset 0 only): its elements and parameters, 0
    // until a frame draws the batch at LOD1.
    uint32_t elementBuffer = 0, parameterBuffer = 0;
    // At inset 0 (LOD0), its buildings as points (building_points.h), in the same order.
    uint32_t pointBuffer = 0;
    uint32_t grammar = 0;
    uint64_t bytes = 0;
    glm::dvec3 cellOrigin{0.0};
    // Cell-local bounds of its vertices, for the occlusion test (min > max: no vertex).
    glm::vec3 boundsMin{1.0f}, boundsMax{0.0f};
    // Each building's run of indices and bounds, for the same test building by building.
    std::vector<render::VolumeBuilding> buildings;
    uint64_t lastUsed = 0;
};

struct VolumeStats {
    uint32_t built = 0;   // since the last beginFrame()
    double buildMs = 0.0; // since the last beginFrame(): expansion and upload
    uint64_t residentBytes = 0;
    uint32_t resident = 0;
};

class VolumeCache {
public:
    VolumeCache(const cells::BatchCatalog& catalog, uint64_t budgetBytes)
        : catalog_(catalog), budget_(budgetBytes) {}
    ~VolumeCache();
    VolumeCache(const VolumeCache&) = delete;
    VolumeCache& operator=(const VolumeCache&) = delete;

    void beginFrame(uint64_t frame);
    // The batch's base volumes, walls set `inset` metres inwards (0 for LOD0), with LOD1's
    // elements and parameters when `lod1` (inset 0 only): built the first time a frame draws
    // the batch at LOD1, since most batches, and all of them in an overview, draw at LOD0 only
    // (the elements take as many bytes again as the walls). Valid until the next acquire() or
    // beginFrame().
    const VolumeMesh& acquire(uint32_t batch, float inset, bool lod1 = false);
    // The batch's mesh if it is resident, else null: neither builds nor counts as a use, so a
    // caller can test its bounds before deciding to draw it.
    const VolumeMesh* find(uint32_t batch, float inset) const;
    VolumeStats stats() const;

private:
    void evict();
    void addLod1(VolumeMesh& mesh, const grammar::ExtrudedSet& extruded);
    uint64_t keyOf(uint32_t batch, float inset) const;

    const cells::BatchCatalog& catalog_;
    uint64_t budget_;
    uint64_t frame_ = 0;
    std::unordered_map<uint64_t, VolumeMesh> meshes_; // by batch key digest and inset
    VolumeStats stats_;
};

} // namespace hexlod::lod
