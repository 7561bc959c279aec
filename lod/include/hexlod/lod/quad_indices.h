// An index buffer of quads, for passes that pull one rectangle a record by gl_VertexID
// (pulled_quad.glsl): quad q is the triangles (4q, 4q+1, 4q+2) and (4q+2, 4q+1, 4q+3), and a
// draw of n records from record r draws its first 6n indices with base vertex 4r. Indexed,
// each corner is shaded once: llvmpipe shaded all six vertices of a non-indexed rectangle,
// and the LOD2 pass's vertex stage took twice as long. Needs a current GL context.
#pragma once

#include <cstdint>

namespace hexlod::lod {

class QuadIndices {
public:
    QuadIndices() = default;
    ~QuadIndices();
    QuadIndices(const QuadIndices&) = delete;
    QuadIndices& operator=(const QuadIndices&) = delete;

    // Makes the buffer hold at least `quads` quads (a buffer exists after the first call, even
    // for none); true when it is a new buffer, which a vertex array holding the old one must
    // be given again.
    bool reserve(uint64_t quads);
    uint32_t buffer() const { return buffer_; }
    uint64_t quads() const { return quads_; }
    uint64_t byteSize() const { return quads_ * 6 * sizeof(uint32_t); }

private:
    uint32_t buffer_ = 0;
    uint64_t quads_ = 0;
};

} // namespace hexlod::lod
