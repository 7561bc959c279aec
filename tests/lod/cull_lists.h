// The GPU cull pass's draw lists against the CPU reference's, entry by entry, whatever order
// the atomics gave them.
#pragma once

#include "hexlod/lod/cpu_cull.h"

#include <algorithm>
#include <cstring>
#include <tuple>
#include <vector>

namespace hexlod::lod {

// A record's identity in a list: every word but the transition factor (which is not part of
// the decision).
using ListEntryId = std::tuple<uint32_t, uint32_t, uint32_t, uint32_t, uint32_t, uint32_t, uint32_t>;

inline ListEntryId identity(const gpu::GpuTerminal& t) {
    uint32_t p[3];
    std::memcpy(p, &t.position, sizeof p);
    return {p[0], p[1], p[2], t.orientation.x, t.orientation.y, t.size, t.shapeAndDepth};
}

// The entries [first, first + count) of a list the GPU pass wrote, sorted.
inline std::vector<ListEntryId> sortedIds(const std::vector<gpu::GpuTerminal>& list, uint32_t first,
                                          uint32_t count) {
    std::vector<ListEntryId> ids;
    for (uint32_t i = 0; i < count; ++i) ids.push_back(identity(list.at(first + i)));
    std::sort(ids.begin(), ids.end());
    return ids;
}

// The reference's entries of LOD `lod` (0: all of them), sorted.
inline std::vector<ListEntryId> sortedIds(const std::vector<CulledTerminal>& entries, uint32_t lod) {
    std::vector<ListEntryId> ids;
    for (const CulledTerminal& e : entries)
        if (lod == 0 || e.lod == lod) ids.push_back(identity(e.record));
    std::sort(ids.begin(), ids.end());
    return ids;
}

} // namespace hexlod::lod
