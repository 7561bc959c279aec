// Reading a buffer back through the staging copy: the bytes asked for, from the offset asked
// for, whatever the order and sizes of the reads.
#include "gl_fixture.h"

#include "hexlod/render/buffer_readback.h"

#include <cstdint>
#include <numeric>
#include <vector>

namespace hexlod::render {
namespace {

class BufferReadbackTest : public GlTest {};

TEST_F(BufferReadbackTest, ReadsTheBytesAskedForFromTheOffsetAskedFor) {
    std::vector<uint32_t> values(1000);
    std::iota(values.begin(), values.end(), 7u);
    GLuint source = 0;
    gl::glCreateBuffers(1, &source);
    gl::glNamedBufferStorage(source, GLsizeiptr(values.size() * 4), values.data(), 0);

    BufferReadback readback;
    EXPECT_EQ(readback.byteSize(), 0u);
    uint32_t one = 0;
    readback.read(source, 4 * 10, 4, &one);
    EXPECT_EQ(one, 17u);
    const uint64_t small = readback.byteSize();
    EXPECT_GE(small, 4u);

    // A larger read grows the staging buffer and still reads from the start it names.
    std::vector<uint32_t> tail(900);
    readback.read(source, 4 * 100, tail.size() * 4, tail.data());
    EXPECT_EQ(tail.front(), 107u);
    EXPECT_EQ(tail.back(), 1006u);
    EXPECT_GE(readback.byteSize(), tail.size() * 4);

    // A smaller read after it reuses the grown buffer.
    const uint64_t grown = readback.byteSize();
    readback.read(source, 0, 8, &tail[0]);
    EXPECT_EQ(tail[0], 7u);
    EXPECT_EQ(tail[1], 8u);
    EXPECT_EQ(readback.byteSize(), grown);
    gl::glDeleteBuffers(1, &source);
}

TEST_F(BufferReadbackTest, ReadingNothingTouchesNeitherTheOutputNorTheGl) {
    BufferReadback readback;
    uint32_t untouched = 42;
    readback.read(0, 0, 0, &untouched);
    EXPECT_EQ(untouched, 42u);
    EXPECT_EQ(readback.byteSize(), 0u);
}

} // namespace
} // namespace hexlod::render
