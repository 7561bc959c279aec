// The quad index buffer the pulled-rectangle passes draw over: two counter-clockwise
// triangles a quad over its four corners, growing only when asked for more.
#include "../render/gl_fixture.h"

#include "hexlod/lod/quad_indices.h"
#include "hexlod/render/gl_api.h"

#include <glm/vec2.hpp>

#include <vector>

namespace hexlod::lod {
namespace {

class QuadIndicesTest : public render::GlTest {};

std::vector<uint32_t> readIndices(const QuadIndices& quads) {
    std::vector<uint32_t> indices(quads.quads() * 6);
    gl::glGetNamedBufferSubData(quads.buffer(), 0, GLsizeiptr(indices.size() * sizeof(uint32_t)),
                                indices.data());
    return indices;
}

TEST_F(QuadIndicesTest, EveryQuadIsTwoTrianglesOverItsOwnFourCornersAndTheBufferGrowsOnlyWhenAsked) {
    QuadIndices quads;
    EXPECT_EQ(quads.byteSize(), 0u);
    ASSERT_TRUE(quads.reserve(0)) << "a draw of no records still needs a buffer bound";
    EXPECT_NE(quads.buffer(), 0u);
    ASSERT_TRUE(quads.reserve(3) || quads.quads() >= 3);
    ASSERT_GE(quads.quads(), 3u);
    const uint32_t first = quads.buffer();
    EXPECT_FALSE(quads.reserve(quads.quads())) << "enough already: the same buffer";
    EXPECT_EQ(quads.buffer(), first);
    ASSERT_TRUE(quads.reserve(5000));
    EXPECT_GE(quads.quads(), 5000u);
    EXPECT_EQ(quads.byteSize(), quads.quads() * 6 * sizeof(uint32_t));
    const std::vector<uint32_t> indices = readIndices(quads);
    ASSERT_EQ(indices.size(), quads.quads() * 6);
    // Corners: bit 0 high x, bit 1 high y (pulled_quad.glsl). Both triangles of each quad
    // turn counter-clockwise in those coordinates, and together cover its four corners.
    const auto corner = [](uint32_t index) { return glm::vec2(float(index & 1u), float((index >> 1) & 1u)); };
    for (uint64_t q = 0; q < quads.quads(); ++q) {
        for (uint32_t t = 0; t < 2; ++t) {
            const uint32_t* triangle = &indices[q * 6 + t * 3];
            for (uint32_t v = 0; v < 3; ++v) ASSERT_EQ(triangle[v] / 4, q) << "quad " << q;
            const glm::vec2 a = corner(triangle[0]), b = corner(triangle[1]), c = corner(triangle[2]);
            const float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
            ASSERT_GT(area, 0.0f) << "quad " << q << " triangle " << t;
        }
        uint32_t seen = 0;
        for (uint32_t v = 0; v < 6; ++v) seen |= 1u << (indices[q * 6 + v] % 4);
        ASSERT_EQ(seen, 0xfu) << "quad " << q;
    }
}

} // namespace
} // namespace hexlod::lod
