#include "hexlod/lod/quad_indices.h"
#include "hexlod/render/gl_api.h"

#include <algorithm>
#include <vector>

namespace hexlod::lod {

QuadIndices::~QuadIndices() {
    if (buffer_) gl::glDeleteBuffers(1, &buffer_);
}

bool QuadIndices::reserve(uint64_t quads) {
    if (buffer_ && quads <= quads_) return false;
    // Doubling: the largest draw grows with the records in view, and a buffer remade every
    // frame would cost more than the headroom. Indices reach 4 q + 3, within 32 bits.
    quads = std::min<uint64_t>(std::max<uint64_t>({quads, 2 * quads_, 1024}), (uint64_t(1) << 30) - 1);
    std::vector<uint32_t> indices;
    indices.reserve(quads * 6);
    for (uint32_t q = 0; q < quads; ++q)
        for (uint32_t corner : {0u, 1u, 2u, 2u, 1u, 3u}) indices.push_back(4 * q + corner);
    if (buffer_) gl::glDeleteBuffers(1, &buffer_);
    gl::glCreateBuffers(1, &buffer_);
    gl::glNamedBufferStorage(buffer_, GLsizeiptr(indices.size() * sizeof(uint32_t)), indices.data(), 0);
    quads_ = quads;
    return true;
}

} // namespace hexlod::lod
