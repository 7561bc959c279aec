// Where LOD0's wall texture is its mean: boxes wholly beyond 0.75 * 3 m * screenScale along
// the view, and nothing else.
#include "hexlod/lod/wall_texture_mean.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>

namespace hexlod::lod {
namespace {

constexpr float kScreenScale = 100.0f; // the depth: 225 m
const glm::vec3 kNorth(0.0f, 1.0f, 0.0f);

TEST(WallTextureMean, ABoxWhollyBeyondTheDepthIsAtItsMean) {
    EXPECT_TRUE(wallTextureIsMean({-10, 300, 0}, {10, 320, 30}, kNorth, kScreenScale));
    EXPECT_TRUE(wallTextureIsMean({-10, 225, 0}, {10, 245, 30}, kNorth, kScreenScale)); // at it
    EXPECT_FALSE(wallTextureIsMean({-10, 224, 0}, {10, 320, 30}, kNorth, kScreenScale));
    EXPECT_FALSE(wallTextureIsMean({-10, 300, 0}, {10, 320, 30}, kNorth, 200.0f)); // 450 m at twice the scale
}

TEST(WallTextureMean, TheNearestCornerAlongAnObliqueViewDecides) {
    const glm::vec3 northEast = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f));
    // The nearest corner (200, 200) lies 283 m along the view.
    EXPECT_TRUE(wallTextureIsMean({200, 200, 0}, {220, 220, 10}, northEast, kScreenScale));
    EXPECT_FALSE(wallTextureIsMean({200, 200, 0}, {220, 220, 10}, northEast, 130.0f)); // 292.5 m
    // Looking down from above: the roof is nearest.
    EXPECT_TRUE(wallTextureIsMean({-10, -10, -400}, {10, 10, -300}, {0, 0, -1}, kScreenScale));
}

TEST(WallTextureMean, BoxesAroundOrBehindTheCameraAndBadInputsAreNot) {
    EXPECT_FALSE(wallTextureIsMean({-10, -10, -10}, {10, 10, 10}, kNorth, kScreenScale));
    EXPECT_FALSE(wallTextureIsMean({-10, -320, 0}, {10, -300, 30}, kNorth, kScreenScale));
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    EXPECT_FALSE(wallTextureIsMean({-10, 300, 0}, {10, 320, 30}, kNorth, 0.0f));
    EXPECT_FALSE(wallTextureIsMean({-10, 300, 0}, {10, 320, 30}, kNorth, -1.0f));
    EXPECT_FALSE(wallTextureIsMean({-10, 300, 0}, {10, 320, 30}, kNorth, nan));
    EXPECT_FALSE(wallTextureIsMean({nan, 300, 0}, {10, 320, 30}, kNorth, kScreenScale));
    EXPECT_FALSE(wallTextureIsMean({-10, 300, 0}, {10, 320, 30}, {nan, nan, nan}, kScreenScale));
    EXPECT_FALSE(wallTextureIsMean({-inf, 300, 0}, {10, 320, 30}, {1, 0, 0}, kScreenScale));
}

TEST(WallTextureMean, TheShaderReadsTheSameSizes) {
    float bay = 0.0f, storey = 0.0f, cycles = 0.0f;
    ASSERT_EQ(std::sscanf(wallTextureSizesGlsl().c_str(),
                          "const vec2 kWallBay = vec2(%f, %f); // metres along the wall, up it\n"
                          "const float kWallMeanCyclesPerPixel = %f;",
                          &bay, &storey, &cycles),
              3);
    EXPECT_EQ(bay, kWallBayMetres);
    EXPECT_EQ(storey, kWallStoreyMetres);
    EXPECT_EQ(cycles, kWallMeanCyclesPerPixel);
}

} // namespace
} // namespace hexlod::lod
