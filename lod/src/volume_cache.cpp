// Building, uploading and evicting base volume meshes.
#include "hexlod/lod/volume_cache.h"
#include "hexlod/lod/building_points.h"
#include "hexlod/lod/lod1_elements.h"
#include "hexlod/render/base_volume_mesh.h"
#include "hexlod/render/gl_api.h"

#include <chrono>
#include <cstring>

namespace hexlod::lod {
namespace {

void release(VolumeMesh& mesh) {
    releaseVolumeMesh(mesh.gpu);
    for (uint32_t buffer : {mesh.elementBuffer, mesh.parameterBuffer, mesh.pointBuffer})
        if (buffer) gl::glDeleteBuffers(1, &buffer);
}

} // namespace

VolumeCache::~VolumeCache() {
    for (auto& [key, mesh] : meshes_) release(mesh);
}

void VolumeCache::beginFrame(uint64_t frame) {
    frame_ = frame;
    stats_.built = 0;
    stats_.buildMs = 0.0;
    evict();
}

void VolumeCache::evict() {
    // What the previous frame drew stays even over budget: the next frame most likely draws it
    // again, and a view that needs more than the budget would otherwise rebuild the same meshes
    // frame after frame (the thesis city's overview drew 366 MB of volumes before they were
    // packed and LOD1's elements became lazy; 129 MB since).
    while (stats_.residentBytes > budget_) {
        auto oldest = meshes_.end();
        for (auto it = meshes_.begin(); it != meshes_.end(); ++it) {
            if (it->second.lastUsed + 1 >= frame_) continue;
            if (oldest == meshes_.end() || it->second.lastUsed < oldest->second.lastUsed) oldest = it;
        }
        if (oldest == meshes_.end()) return; // all drawn by the previous frame
        stats_.residentBytes -= oldest->second.bytes;
        release(oldest->second);
        meshes_.erase(oldest);
    }
}

uint64_t VolumeCache::keyOf(uint32_t batch, float inset) const {
    uint32_t insetBits;
    std::memcpy(&insetBits, &inset, sizeof insetBits);
    return catalog_.key(batch).digest() ^ (uint64_t(insetBits) * 0x9e3779b97f4a7c15ull);
}

const VolumeMesh* VolumeCache::find(uint32_t batch, float inset) const {
    auto it = meshes_.find(keyOf(batch, inset));
    return it == meshes_.end() ? nullptr : &it->second;
}

// LOD1's elements and parameters for a mesh at inset 0, from the batch's extruded set.
void VolumeCache::addLod1(VolumeMesh& mesh, const grammar::ExtrudedSet& extruded) {
    const std::vector<GpuLod1Element> elements = packLod1Elements(extruded, catalog_.scene().config.seed);
    mesh.elementBuffer = immutableBuffer(elements.data(), elements.size() * sizeof(GpuLod1Element));
    mesh.parameterBuffer =
        immutableBuffer(extruded.parameters.data(), extruded.parameters.size() * sizeof(float));
    const uint64_t bytes =
        elements.size() * sizeof(GpuLod1Element) + extruded.parameters.size() * sizeof(float);
    mesh.bytes += bytes;
    stats_.residentBytes += bytes;
}

const VolumeMesh& VolumeCache::acquire(uint32_t batch, float inset, bool lod1) {
    const uint64_t key = keyOf(batch, inset);
    const auto start = std::chrono::steady_clock::now();
    const auto counted = [&](VolumeMesh& mesh) -> const VolumeMesh& {
        stats_.buildMs +=
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        return mesh;
    };
    if (auto it = meshes_.find(key); it != meshes_.end()) {
        VolumeMesh& mesh = it->second;
        mesh.lastUsed = frame_;
        if (!lod1 || mesh.elementBuffer || inset != 0.0f) return mesh;
        addLod1(mesh, catalog_.expandExtruded(batch));
        return counted(mesh);
    }
    const grammar::ExtrudedSet extruded = catalog_.expandExtruded(batch);
    VolumeMesh mesh;
    const render::TerminalMesh shell = render::buildBaseVolumes(extruded, inset, &mesh.buildings);
    mesh.cellOrigin = catalog_.cellOrigin(catalog_.batch(batch).cell);
    mesh.grammar = catalog_.batch(batch).grammar;
    mesh.lastUsed = frame_;
    mesh.indexCount = uint32_t(shell.indices.size());
    render::vertexBounds(shell.vertices, mesh.boundsMin, mesh.boundsMax);
    mesh.gpu = uploadVolumeMesh(shell);
    mesh.bytes = mesh.gpu.bytes + mesh.buildings.size() * sizeof(render::VolumeBuilding);
    if (inset == 0.0f) {
        const std::vector<GpuBuildingPoint> points = packBuildingPoints(mesh.buildings);
        mesh.pointBuffer = immutableBuffer(points.data(), points.size() * sizeof(GpuBuildingPoint));
        mesh.bytes += points.size() * sizeof(GpuBuildingPoint);
    }
    stats_.residentBytes += mesh.bytes;
    ++stats_.built;
    VolumeMesh& placed = meshes_[key] = std::move(mesh);
    if (lod1 && inset == 0.0f) addLod1(placed, extruded);
    return counted(placed);
}

VolumeStats VolumeCache::stats() const {
    VolumeStats s = stats_;
    s.resident = uint32_t(meshes_.size());
    return s;
}

} // namespace hexlod::lod
