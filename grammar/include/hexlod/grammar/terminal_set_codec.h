// The terminal set on the wire and on disk (docs/protocol.md, "Terminal set, version 1"):
// a small little-endian header, then the records transposed into columns (positions and
// building ids delta-coded) and compressed with zstd. Columns are what makes a 32-byte
// record shrink to about 3 bytes: deltas are small and orientations and sizes repeat.
#pragma once

#include "hexlod/grammar/terminal_set.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace hexlod::grammar {

inline constexpr uint32_t kTerminalSetFormatVersion = 1;
inline constexpr size_t kTerminalSetFixedHeaderBytes = 92;
// A decoder refuses more records than this (4 GiB decoded), whatever the header says.
inline constexpr uint64_t kTerminalSetMaxRecords = uint64_t(1) << 27;

// Encodes `set` byte-exactly. A set whose countPerShape does not sum to its record count,
// or whose records are not grouped by shape as countPerShape says, encodes to a payload
// that decodeTerminalSet rejects.
std::vector<uint8_t> encodeTerminalSet(const TerminalSet& set, int zstdLevel = 3);

// Decodes a payload into `out`. On truncated, corrupt or foreign input it returns false,
// leaves `out` unspecified and says why in `error`. Memory use follows the bytes that
// actually decompress, never a size the header claims.
bool decodeTerminalSet(std::span<const uint8_t> payload, TerminalSet& out, std::string& error);

// The fixed header alone, for callers that route or index payloads without decoding them
// (the disk tier checks its file header against it).
struct TerminalSetPayloadInfo {
    uint32_t version = 0;
    uint64_t checksum = 0; // of the decoded content: header fields, counts and the column body
    TerminalSetHeader header;
    uint64_t recordCount = 0;
    uint64_t bodyBytes = 0; // the zstd frame
    uint32_t shapeCount = 0;
};
bool peekTerminalSet(std::span<const uint8_t> payload, TerminalSetPayloadInfo& info, std::string& error);

// The 64-bit checksum the format uses: four XXH64-style lanes over 8-byte words (not
// bit-compatible with XXH64), fast enough to run on every decode.
uint64_t checksum64(std::span<const uint8_t> bytes, uint64_t seed = 0);

} // namespace hexlod::grammar
