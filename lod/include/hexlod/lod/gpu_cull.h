// The GPU cull and LOD pass (thesis §7.5.3): terminal_cull.comp over every terminal of the
// resident batches in view (but pages wholly outside the frustum or behind the occlusion
// tiles, skipped on the CPU), then
// cull_finalize.comp turning its counters into indirect draw commands. Needs a current GL context. Its
// buffers grow when a frame needs more and are otherwise reused frame after frame.
#pragma once

#include "hexlod/lod/cull_inputs.h"
#include "hexlod/render/buffer_readback.h"
#include "hexlod/render/shader_program.h"

#include <glm/vec4.hpp>

#include <span>
#include <string>
#include <vector>

namespace hexlod::lod {

// Where a global shape's mesh lies in the mesh buffers, for its LOD4 draw command.
struct MeshDrawInfo {
    uint32_t indexCount = 0, firstIndex = 0;
    int32_t baseVertex = 0;
};

// The commands in commandBuffer(), DrawElementsIndirectCommands of 20 bytes: shapeCount for
// LOD4, then shapeCount for LOD2 entries in listBuffer(), then as many for LOD3 entries in
// lod3ListBuffer(). The impostor commands draw from a QuadIndices buffer holding at least the
// largest LOD2 or LOD3 list (DrawListLayout).
inline constexpr uint32_t kCommandStride = 20;

class GpuCull {
public:
    GpuCull() = default;
    ~GpuCull();
    GpuCull(const GpuCull&) = delete;
    GpuCull& operator=(const GpuCull&) = delete;

    bool init(std::string& error);

    // Culls the batches of `inputs`, whose records lie in `arena`, and writes draw lists and
    // commands. `meshes` has one entry per global shape.
    void run(const CullInputs& inputs, uint32_t arena, std::span<const MeshDrawInfo> meshes);

    const DrawListLayout& layout() const { return layout_; }
    // The last run's terminals culled one by one, and those skipped with their page (of
    // which the rest count why: behind the occlusion tiles, facing away, billboard trees).
    struct PageStats {
        uint64_t terminals = 0, skippedTerminals = 0, occludedTerminals = 0, facingAwayTerminals = 0,
                 billboardTerminals = 0;
    };
    PageStats pageStats() const { return stats_; }
    uint32_t shapeCount() const { return shapeCount_; }
    // The most draw-list records one storage block holds (CullInputs::maxListRecords).
    uint64_t maxListRecords() const { return maxListRecords_; }
    uint32_t listBuffer() const { return buffers_[kLists].id; }
    uint32_t lod3ListBuffer() const { return buffers_[kLod3Lists].id; }
    uint32_t frameBuffer() const { return buffers_[kFrame].id; } // the CullFrame uniform block
    uint32_t commandBuffer() const { return buffers_[kCommands].id; }
    uint64_t byteSize() const; // GPU memory of the pass's buffers

    // Per shape: LOD4 entries, 0, LOD3 and LOD2 entries (waits for the pass).
    std::vector<glm::uvec4> readCounters();
    // Terminals the occlusion test culled one by one (waits for the pass).
    uint32_t readOccluded();
    // The draw lists as written, LOD4 and LOD2 and then LOD3 (tests; wait for the pass).
    std::vector<gpu::GpuTerminal> readLists();
    std::vector<gpu::GpuTerminal> readLod3Lists();

private:
    enum BufferIndex {
        kFrame,
        kBatches,
        kWorkgroups,
        kShapes,
        kCounters,
        kLists,
        kMeshes,
        kCommands,
        kOccluded,
        kCoarse,
        kLod3Lists,
        kLod3Bases,
        kBufferCount
    };
    struct Buffer {
        uint32_t id = 0;
        uint64_t capacity = 0;
    };
    // Makes buffer `index` hold at least `bytes`, growing it by doubling.
    void reserve(BufferIndex index, uint64_t bytes);
    std::vector<gpu::GpuTerminal> readRecords(BufferIndex index, uint64_t count);

    render::ShaderProgram cull_, finalize_;
    Buffer buffers_[kBufferCount];
    render::BufferReadback readback_;
    DrawListLayout layout_;
    PageStats stats_;
    uint32_t shapeCount_ = 0;
    uint64_t maxListRecords_ = 0;
};

// The lod module's embedded GLSL (lod/shaders/ and cull_shared.h) on top of render's and
// impostor's.
render::ShaderLibrary lodShaderLibrary();

} // namespace hexlod::lod
