// The zstd plumbing both payload codecs share (terminal sets and extruded sets,
// docs/protocol.md): one compression and one decompression context per thread, and a
// decompressor that grows its output with what the frame really delivers, so a header
// that claims gigabytes costs nothing unless the frame holds them. The output is a scratch
// buffer kept per thread: a fresh one per payload cost more in page faults and zero-filling
// than zstd took to decode into it.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

namespace hexlod::grammar::detail {

template <typename T> void put(std::vector<uint8_t>& out, size_t offset, T value) {
    std::memcpy(out.data() + offset, &value, sizeof(T));
}
template <typename T> T get(std::span<const uint8_t> in, size_t offset) {
    T value;
    std::memcpy(&value, in.data() + offset, sizeof(T));
    return value;
}

inline uint32_t zigzag(uint32_t delta) {
    return (delta << 1) ^ static_cast<uint32_t>(static_cast<int32_t>(delta) >> 31);
}
inline uint32_t unzigzag(uint32_t z) {
    return (z >> 1) ^ (0u - (z & 1u));
}

// Compresses `body` into one zstd frame appended to `out` after its first `offset` bytes
// (`out` is resized to offset + frame size, its first bytes kept). Returns the frame size.
// The frame is made in this thread's scratch and copied: a vector sized to zstd's bound was
// zero-filled and page-faulted in at the raw body's size for every payload.
size_t compressFrame(std::span<const uint8_t> body, int level, std::vector<uint8_t>& out, size_t offset);

// This thread's buffer for an encoder to lay its body out in before compressFrame: at least
// `bytes` long, uninitialised, valid until the thread's next call. An encoder declares a
// ScratchRelease first.
uint8_t* encoderBody(size_t bytes);

// Decompresses one frame that must decode to exactly `expected` bytes and fill `frame`
// completely. `body` then views the bytes, in this thread's scratch buffer: valid until the
// thread's next call. On failure returns false with `error` saying why (not a frame,
// corrupt, truncated, too long or short, trailing bytes).
bool decompressFrame(std::span<const uint8_t> frame, uint64_t expected, std::span<const uint8_t>& body,
                     std::string& error);

// The most scratch a thread keeps between payloads, per buffer. A decoder declares a
// ScratchRelease before it decompresses, and an encoder before it asks for encoderBody: it
// releases a larger body's buffer when the codec returns.
constexpr size_t kKeptScratchBytes = size_t(32) << 20; // the thesis city's largest body is 27 MB
struct ScratchRelease {
    ScratchRelease() = default;
    ScratchRelease(const ScratchRelease&) = delete;
    ScratchRelease& operator=(const ScratchRelease&) = delete;
    ~ScratchRelease();
};
// The bytes of scratch this thread holds now, per buffer (what a ScratchRelease leaves it is
// testable).
struct ThreadScratch {
    size_t decode = 0; // decompressFrame's output
    size_t body = 0;   // encoderBody
    size_t frame = 0;  // compressFrame's output
};
ThreadScratch threadScratch();

} // namespace hexlod::grammar::detail
