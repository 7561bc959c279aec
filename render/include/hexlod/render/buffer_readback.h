// Reads back what shaders wrote into a buffer through a staging buffer of its own. A driver
// that sees the CPU read a buffer the GPU also writes may move that whole buffer into host
// memory (NVIDIA's driver says so in a performance warning), and the shaders' atomics on it
// then cross the bus every frame. Copying into a staging buffer first keeps the source in
// video memory; only the staging buffer, made for client reads, is ever read by the CPU.
#pragma once

#include <cstdint>

namespace hexlod::render {

class BufferReadback {
public:
    BufferReadback() = default;
    ~BufferReadback();
    BufferReadback(const BufferReadback&) = delete;
    BufferReadback& operator=(const BufferReadback&) = delete;

    // Copies `bytes` of `source` from `offset` into `out`, after the shader writes issued
    // before it (waits for them). Needs a current GL context.
    void read(uint32_t source, uint64_t offset, uint64_t bytes, void* out);

    uint64_t byteSize() const { return capacity_; } // the staging buffer's GPU memory

private:
    uint32_t staging_ = 0;
    uint64_t capacity_ = 0;
};

} // namespace hexlod::render
