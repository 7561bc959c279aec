// The extruded set on the wire (docs/protocol.md, "Extruded set, version 1"): what LOD0 and
// LOD1 draw for a batch, in the same transpose-then-compress style as the terminal-set codec.
// A fixed little-endian header, then every field as a column of 32-bit words (positions and
// building ids delta-coded), compressed as one zstd frame.
#pragma once

#include "hexlod/grammar/extruded_set.h"
#include "hexlod/grammar/terminal_set.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace hexlod::grammar {

inline constexpr uint32_t kExtrudedSetFormatVersion = 1;
inline constexpr size_t kExtrudedSetHeaderBytes = 96;
// A decoder refuses counts beyond these, whatever the header says.
inline constexpr uint32_t kExtrudedSetMaxBuildings = 1u << 24;
inline constexpr uint32_t kExtrudedSetMaxVertices = 1u << 28;
inline constexpr uint32_t kExtrudedSetMaxElements = 1u << 28;
inline constexpr uint32_t kExtrudedSetMaxParameters = 4096; // per building

// What the payload says about its batch; the extruded set itself carries none of it.
struct ExtrudedSetHeader {
    CellCoord cell;
    uint32_t grammar = 0;      // index of the grammar in the scene
    uint64_t grammarHash = 0;  // CompiledGrammar::contentHash
    uint64_t key = 0;          // cache key digest
    double cellOrigin[3] = {}; // world position the set's cell-local coordinates are relative to
};

// Encodes byte-exactly what decodeExtrudedSet gives back. The set must be contiguous as
// expandBatch builds it: building i's vertices, elements and parameters follow building
// i - 1's, and every building has the same number of parameters. Throws
// std::invalid_argument naming the first building that breaks this.
std::vector<uint8_t> encodeExtrudedSet(const ExtrudedSetHeader& header, const ExtrudedSet& set,
                                       int zstdLevel = 3);

// Decodes a payload. On truncated, corrupt or foreign input returns false, leaves the outputs
// unspecified and says why in `error`. Memory follows the bytes that really decompress, never
// a count the header claims.
bool decodeExtrudedSet(std::span<const uint8_t> payload, ExtrudedSetHeader& header, ExtrudedSet& set,
                       std::string& error);

struct ExtrudedSetPayloadInfo {
    uint32_t version = 0;
    uint64_t checksum = 0;
    ExtrudedSetHeader header;
    uint32_t buildings = 0, vertices = 0, elements = 0;
    uint32_t parametersPerBuilding = 0;
    uint64_t bodyBytes = 0;
};
// The fixed header alone, checked for limits and size.
bool peekExtrudedSet(std::span<const uint8_t> payload, ExtrudedSetPayloadInfo& info, std::string& error);

} // namespace hexlod::grammar
