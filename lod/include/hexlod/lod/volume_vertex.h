// Base volumes as the GPU holds them (VolumeCache): 24 bytes a vertex where a MeshVertex takes
// 36 (the normal in 10-bit signed components, the uv's element index alone), and 16-bit
// indices where a batch's mesh has fewer than 65,536 vertices. The thesis city's overview
// draws several hundred megabytes of base volumes a frame: their budget, not the shading,
// bounds how many stay resident. volume.vert reads this layout.
#pragma once

#include "hexlod/render/terminal_mesh.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace hexlod::lod {

struct VolumeVertex {
    glm::vec3 position; // cell-local metres
    uint32_t normal;    // GL_INT_2_10_10_10_REV, normalized (packSnorm10)
    float element;      // the wall's extruded-set element (MeshVertex::uv.x on walls), -1 elsewhere
    uint32_t rgba;
};
static_assert(sizeof(VolumeVertex) == 24, "VolumeVertex is bound as a tightly packed 24-byte stride");

// A unit vector in three signed normalized 10-bit components (x in the low bits); a component
// outside [-1, 1] is clamped, a NaN one is 0. unpackSnorm10 is what the GL reads back.
uint32_t packSnorm10(const glm::vec3& unit);
glm::vec3 unpackSnorm10(uint32_t packed);

// The mesh's vertices as VolumeVertex: walls keep their element (uv = (element, 1)), every
// other vertex is -1 (render::buildBaseVolumes).
std::vector<VolumeVertex> packVolumeVertices(std::span<const render::MeshVertex> vertices);

// A base volume mesh on the GPU: its vertex array (the layout above, vertex buffer binding 0)
// over its two buffers; the draws read `indexType` indices of `indexSize` bytes.
struct VolumeBuffers {
    uint32_t vao = 0, vertexBuffer = 0, indexBuffer = 0;
    uint32_t indexType = 0, indexSize = 0; // GL_UNSIGNED_SHORT (2) or GL_UNSIGNED_INT (4)
    uint64_t bytes = 0;                    // both buffers
};
VolumeBuffers uploadVolumeMesh(const render::TerminalMesh& mesh);
void releaseVolumeMesh(VolumeBuffers& buffers);

// An immutable GL buffer of `bytes` bytes from `data` (at least 4: the GL refuses an empty
// one), for a base volume's buffers and LOD1's elements beside them.
uint32_t immutableBuffer(const void* data, size_t bytes);

} // namespace hexlod::lod
