// The CPU reference of the cull and LOD pass: the same decision (cull_shared.h) over the same
// inputs, producing the same per-shape lists, so tests can hold the GPU pass to it exactly and
// the walkthrough can run with no GL at all.
#pragma once

#include "hexlod/lod/cull_inputs.h"

#include <array>
#include <vector>

namespace hexlod::lod {

struct CulledTerminal {
    gpu::GpuTerminal record; // as the GPU writes it: camera-relative corner, global shape id
    uint32_t lod = 0;        // HEXLOD_LOD4, HEXLOD_LOD3 or HEXLOD_LOD2
};

struct CullResult {
    // Per global shape: LOD4 entries, then impostor entries (LOD3 and LOD2), in batch order.
    std::vector<std::vector<CulledTerminal>> lod4, impostor;
    std::array<uint64_t, 5> terminalsPerLod{}; // index = LOD (0 and 1 unused here)
    uint64_t culled = 0;
    uint64_t occluded = 0; // of the culled, those the occlusion tiles hid
};

CullResult cullOnCpu(const CullInputs& inputs);

} // namespace hexlod::lod
