// The terminal set: one 32-byte record per terminal, laid out for direct std430 upload
// (thesis §4.4: the compact output that stands for full facade geometry).
#pragma once

#include "hexlod/grammar/bulk_allocator.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <vector>

namespace hexlod::grammar {

// std430 layout, mirrored by `struct Terminal` in GLSL:
//   vec3 position; uint building; uvec2 orientation; uint size; uint shapeAndDepth;
struct TerminalRecord {
    float position[3];       // scope origin (its corner), metres relative to the batch's cell origin
    uint32_t building;       // building id, for edits and picking
    uint32_t orientation[2]; // unit quaternion (x, y, z, w) as 4 x snorm16, w >= 0
    uint32_t size;           // scope width and height as two halves
    uint32_t shapeAndDepth;  // shape id in the low 16 bits, depth ratio as a half in the high 16
};
static_assert(sizeof(TerminalRecord) == 32, "the terminal record must stay at 32 bytes");
static_assert(alignof(TerminalRecord) == 4);

// A terminal decoded back to floats (tests, CPU culling and readers of the wire format).
struct Terminal {
    glm::vec3 position{0.0f};
    glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec2 size{0.0f};
    float depthRatio = 0.0f;
    uint16_t shape = 0;
    uint32_t building = 0;

    glm::vec3 axisX() const { return orientation * glm::vec3(1, 0, 0); }
    glm::vec3 axisY() const { return orientation * glm::vec3(0, 1, 0); }
    glm::vec3 normal() const { return orientation * glm::vec3(0, 0, 1); }
};

// `x`, `y`, `z` must be an orthonormal right-handed basis.
TerminalRecord packTerminal(const glm::vec3& position, const glm::vec3& x, const glm::vec3& y,
                            const glm::vec3& z, const glm::vec2& size, float depthRatio, uint16_t shape,
                            uint32_t building);
Terminal unpackTerminal(const TerminalRecord& record);

struct CellCoord {
    int32_t q = 0;
    int32_t r = 0;
};

struct TerminalSetHeader {
    CellCoord cell;
    uint32_t grammar = 0;      // index of the grammar in the scene
    uint32_t reserved = 0;     // keeps the header free of padding, so its bytes are defined
    uint64_t grammarHash = 0;  // CompiledGrammar::contentHash
    uint64_t key = 0;          // cache key, filled by the cache
    double cellOrigin[3] = {}; // world position that record positions are relative to
};

static_assert(sizeof(TerminalSetHeader) == 56);

// One batch: records sorted by shape (then building, then derivation order), so each
// shape's instances are one contiguous range for instanced drawing.
struct TerminalSet {
    TerminalSetHeader header;
    std::vector<uint32_t> countPerShape;
    std::vector<TerminalRecord, BulkAllocator<TerminalRecord>> records;

    size_t byteSize() const {
        return sizeof(TerminalSetHeader) + countPerShape.size() * sizeof(uint32_t) +
               records.size() * sizeof(TerminalRecord);
    }
    // The memory it holds: byteSize() and the rest of its records' block (bulk_allocator.h),
    // what a memory budget must count.
    size_t heldBytes() const {
        return byteSize() + bulkBlockBytes(records.data(), records.capacity() * sizeof(TerminalRecord)) -
               records.size() * sizeof(TerminalRecord);
    }
    // First record of `shape`, for drawing one shape's instances.
    size_t firstOfShape(uint16_t shape) const;
};

} // namespace hexlod::grammar
