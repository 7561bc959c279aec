// Building, uploading and evicting base volume meshes.
#include "hexlod/lod/volume_cache.h"
#include "hexlod/lod/lod1_elements.h"
#include "hexlod/render/base_volume_mesh.h"
#include "hexlod/render/gl_api.h"
#include "hexlod/render/mesh_vertex_format.h"

#include <chrono>
#include <cstring>

namespace hexlod::lod {
namespace {

void release(VolumeMesh& mesh) {
    gl::glDeleteVertexArrays(1, &mesh.vao);
    for (uint32_t buffer : {mesh.vertexBuffer, mesh.indexBuffer, mesh.elementBuffer, mesh.parameterBuffer})
        if (buffer) gl::glDeleteBuffers(1, &buffer);
}

uint32_t storage(const void* data, size_t bytes) {
    uint32_t buffer = 0;
    gl::glCreateBuffers(1, &buffer);
    gl::glNamedBufferStorage(buffer, GLsizeiptr(std::max<size_t>(bytes, 4)), bytes ? data : nullptr, 0);
    return buffer;
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
    // again, and a view that needs more than the budget (the thesis city's overview draws
    // 360 MB of volumes) would otherwise rebuild the same meshes frame after frame.
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

const VolumeMesh& VolumeCache::acquire(uint32_t batch, float inset) {
    const uint64_t key = keyOf(batch, inset);
    if (auto it = meshes_.find(key); it != meshes_.end()) {
        it->second.lastUsed = frame_;
        return it->second;
    }
    const auto start = std::chrono::steady_clock::now();
    const grammar::ExtrudedSet extruded = catalog_.expandExtruded(batch);
    VolumeMesh mesh;
    const render::TerminalMesh shell = render::buildBaseVolumes(extruded, inset, &mesh.buildings);
    mesh.cellOrigin = catalog_.cellOrigin(catalog_.batch(batch).cell);
    mesh.grammar = catalog_.batch(batch).grammar;
    if (inset == 0.0f) {
        const std::vector<GpuLod1Element> elements = packLod1Elements(extruded, catalog_.scene().config.seed);
        mesh.elementBuffer = storage(elements.data(), elements.size() * sizeof(GpuLod1Element));
        mesh.parameterBuffer =
            storage(extruded.parameters.data(), extruded.parameters.size() * sizeof(float));
        mesh.bytes += elements.size() * sizeof(GpuLod1Element) + extruded.parameters.size() * sizeof(float);
    }
    mesh.lastUsed = frame_;
    mesh.indexCount = uint32_t(shell.indices.size());
    render::vertexBounds(shell.vertices, mesh.boundsMin, mesh.boundsMax);
    mesh.bytes += shell.byteSize() + mesh.buildings.size() * sizeof(render::VolumeBuilding);
    mesh.vertexBuffer = storage(shell.vertices.data(), shell.vertices.size() * sizeof(render::MeshVertex));
    mesh.indexBuffer = storage(shell.indices.data(), shell.indices.size() * sizeof(uint32_t));
    gl::glCreateVertexArrays(1, &mesh.vao);
    gl::glVertexArrayVertexBuffer(mesh.vao, 0, mesh.vertexBuffer, 0, sizeof(render::MeshVertex));
    gl::glVertexArrayElementBuffer(mesh.vao, mesh.indexBuffer);
    render::setMeshVertexFormat(mesh.vao, 0);
    stats_.residentBytes += mesh.bytes;
    ++stats_.built;
    stats_.buildMs +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return meshes_[key] = mesh;
}

VolumeStats VolumeCache::stats() const {
    VolumeStats s = stats_;
    s.resident = uint32_t(meshes_.size());
    return s;
}

} // namespace hexlod::lod
