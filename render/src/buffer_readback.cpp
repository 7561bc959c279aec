#include "hexlod/render/buffer_readback.h"
#include "hexlod/render/gl_api.h"

namespace hexlod::render {

BufferReadback::~BufferReadback() {
    if (staging_) gl::glDeleteBuffers(1, &staging_);
}

void BufferReadback::read(uint32_t source, uint64_t offset, uint64_t bytes, void* out) {
    if (bytes == 0) return;
    if (bytes > capacity_) {
        if (staging_) gl::glDeleteBuffers(1, &staging_);
        // Doubling keeps a slowly growing read (one counter per shape) from reallocating
        // frame after frame.
        capacity_ = capacity_ ? capacity_ : 256;
        while (capacity_ < bytes) capacity_ *= 2;
        gl::glCreateBuffers(1, &staging_);
        // CLIENT_STORAGE asks for host memory: the CPU reads this buffer, the GPU only copies
        // into it.
        gl::glNamedBufferStorage(staging_, GLsizeiptr(capacity_), nullptr,
                                 GL_MAP_READ_BIT | GL_CLIENT_STORAGE_BIT);
    }
    // Shader writes become visible to buffer copies only after this barrier.
    gl::glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl::glCopyNamedBufferSubData(source, staging_, GLintptr(offset), 0, GLsizeiptr(bytes));
    gl::glGetNamedBufferSubData(staging_, 0, GLsizeiptr(bytes), out);
}

} // namespace hexlod::render
