#include "hexlod/grammar/terminal_set.h"

#include <gtest/gtest.h>

#include <cstddef>

namespace hexlod::grammar {
namespace {

TEST(TerminalRecord, Std430Layout) {
    // vec3 position at 0, uint building at 12, uvec2 orientation at 16, uint size at 24,
    // uint shapeAndDepth at 28: the GLSL std430 offsets of the same struct.
    EXPECT_EQ(sizeof(TerminalRecord), 32u);
    EXPECT_EQ(offsetof(TerminalRecord, building), 12u);
    EXPECT_EQ(offsetof(TerminalRecord, orientation), 16u);
    EXPECT_EQ(offsetof(TerminalRecord, size), 24u);
    EXPECT_EQ(offsetof(TerminalRecord, shapeAndDepth), 28u);
}

TEST(TerminalRecord, RoundTripsAnArbitraryFrame) {
    const glm::vec3 x = glm::normalize(glm::vec3(1, 2, 0.5f));
    const glm::vec3 y = glm::normalize(glm::cross(glm::vec3(0, 0, 1), x) * -1.0f + glm::vec3(0, 0, 0.1f));
    const glm::vec3 yo = glm::normalize(y - x * glm::dot(x, y));
    const glm::vec3 z = glm::cross(x, yo);
    const TerminalRecord r =
        packTerminal({12.5f, -3.25f, 100.0f}, x, yo, z, {1.4f, 2.6f}, 0.15f, 513, 123456);
    const Terminal t = unpackTerminal(r);
    EXPECT_EQ(t.position, glm::vec3(12.5f, -3.25f, 100.0f));
    EXPECT_EQ(t.shape, 513);
    EXPECT_EQ(t.building, 123456u);
    EXPECT_NEAR(t.size.x, 1.4f, 1e-3f);
    EXPECT_NEAR(t.size.y, 2.6f, 2e-3f);
    EXPECT_NEAR(t.depthRatio, 0.15f, 1e-3f);
    // snorm16 quaternions hold axes to about 1e-4.
    EXPECT_NEAR(glm::length(t.axisX() - x), 0.0f, 2e-4f);
    EXPECT_NEAR(glm::length(t.axisY() - yo), 0.0f, 2e-4f);
    EXPECT_NEAR(glm::length(t.normal() - z), 0.0f, 2e-4f);
}

TEST(TerminalRecord, OppositeQuaternionSignsPackToTheSameBytes) {
    // A 180 degree turn about z: quat_cast may return w = 0 with either sign of z.
    const TerminalRecord a = packTerminal({}, {-1, 0, 0}, {0, -1, 0}, {0, 0, 1}, {1, 1}, 0, 0, 0);
    const TerminalRecord b = packTerminal({}, {-1, 0, 0}, {0, -1, 0}, {0, 0, 1}, {1, 1}, 0, 0, 0);
    EXPECT_EQ(a.orientation[0], b.orientation[0]);
    EXPECT_EQ(a.orientation[1], b.orientation[1]);
    const Terminal t = unpackTerminal(a);
    EXPECT_NEAR(glm::length(t.axisX() - glm::vec3(-1, 0, 0)), 0.0f, 1e-4f);
}

TEST(TerminalRecord, HalfSizesCoverTenKilometreFacades) {
    const TerminalRecord r = packTerminal({}, {1, 0, 0}, {0, 0, 1}, {0, -1, 0}, {10000.0f, 0.001f}, 0, 0, 0);
    const Terminal t = unpackTerminal(r);
    EXPECT_NEAR(t.size.x, 10000.0f, 10000.0f * 1e-3f);
    EXPECT_NEAR(t.size.y, 0.001f, 0.001f * 1e-3f);
}

} // namespace
} // namespace hexlod::grammar

#include <glm/gtc/packing.hpp>

#include <cstring>
#include <limits>

namespace hexlod::grammar {
namespace {

// The record's own half conversion must agree with glm's reference on every value class.
TEST(TerminalRecord, HalfPackingMatchesTheReference) {
    const float values[] = {0.0f,     -0.0f,
                            1.0f,     -1.0f,
                            0.1f,     2.857142857f,
                            65504.0f, 65519.0f,
                            65520.0f, 1e6f,
                            6.1e-5f,  6.0e-8f,
                            1e-9f,    3.0e-5f,

                            0.33333f, std::numeric_limits<float>::infinity()};
    for (float v : values) {
        const TerminalRecord r = packTerminal({}, {1, 0, 0}, {0, 0, 1}, {0, -1, 0}, {v, -v}, 0.0f, 0, 0);
        EXPECT_EQ(r.size, glm::packHalf2x16(glm::vec2(v, -v))) << v;
    }
    const TerminalRecord nan = packTerminal({}, {1, 0, 0}, {0, 0, 1}, {0, -1, 0},
                                            {std::numeric_limits<float>::quiet_NaN(), 1.0f}, 0.0f, 0, 0);
    EXPECT_TRUE(std::isnan(unpackTerminal(nan).size.x));
    // Exact ties round to even as IEEE 754 does (glm rounds them away from zero): halves are
    // 0.5 apart at 1000, so 1000.25 becomes 1000 and 1000.75 becomes 1001.
    const TerminalRecord ties =
        packTerminal({}, {1, 0, 0}, {0, 0, 1}, {0, -1, 0}, {1000.25f, 1000.75f}, 0.0f, 0, 0);
    EXPECT_EQ(unpackTerminal(ties).size, glm::vec2(1000.0f, 1001.0f));
}

} // namespace
} // namespace hexlod::grammar
