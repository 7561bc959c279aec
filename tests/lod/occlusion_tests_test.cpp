// The CPU occlusion tests against hand-made tiles: a wall 10 m ahead covers the whole view.
#include "hexlod/lod/cull_inputs.h"
#include "hexlod/lod/occlusion_tests.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace hexlod::lod {
namespace {

constexpr double kNear = 0.5, kFar = 5000.0;
constexpr uint32_t kColumns = 4, kRows = 2; // 64 x 32 pixels of 16-pixel tiles

// Looking along +y with +z up: x is right, z up on the screen.
shared::CullFrame frame() {
    shared::CullFrame f{};
    setOcclusion(f, {0, 1, 0}, {0, 0, 1}, 60.0 * M_PI / 180.0, kNear, kFar, 64, 32, kColumns, kRows, 16);
    return f;
}

// Reversed-Z window depth of view distance d, as the tiles hold it.
float depthAt(double d) {
    return float(kNear * kFar / ((kFar - kNear) * d) - kNear / (kFar - kNear));
}

std::vector<float> wallAt(double d) {
    return std::vector<float>(kColumns * kRows, depthAt(d));
}

TEST(OcclusionTests, ABoxBehindTheWallIsHiddenAndOneBeforeItIsNot) {
    const shared::CullFrame f = frame();
    const std::vector<float> tiles = wallAt(10.0);
    EXPECT_TRUE(tilesHideBox(f, &tiles, {-1, 20, -1}, {1, 22, 1}));
    EXPECT_FALSE(tilesHideBox(f, &tiles, {-1, 5, -1}, {1, 7, 1}));
    // Reaching through the wall: its nearest corner is in front.
    EXPECT_FALSE(tilesHideBox(f, &tiles, {-1, 9, -1}, {1, 22, 1}));
    // Behind it by less than the cull pass's margin (a centimetre and a part in 1e4).
    EXPECT_FALSE(tilesHideBox(f, &tiles, {-1, 10.005f, -1}, {1, 12, 1}));
    EXPECT_TRUE(tilesHideBox(f, &tiles, {-1, 10.05f, -1}, {1, 12, 1}));
}

TEST(OcclusionTests, ATileWhereTheWallIsMissingShowsOnlyWhatCoversIt) {
    const shared::CullFrame f = frame();
    std::vector<float> tiles = wallAt(10.0);
    tiles[kColumns - 1] = 0.0f; // the bottom right tile: sky
    // A small box at the centre covers the four middle tiles only.
    EXPECT_TRUE(tilesHideBox(f, &tiles, {-0.5f, 40, -0.5f}, {0.5f, 41, 0.5f}));
    // One far to the right and below covers the gap.
    EXPECT_FALSE(tilesHideBox(f, &tiles, {20, 40, -15}, {22, 41, -13}));
    // The sphere test agrees on both.
    EXPECT_TRUE(tilesHideSphere(f, &tiles, {0, 40.5f, 0, 0.9f}, HEXLOD_OCCLUSION_MAX_TILES));
    EXPECT_FALSE(tilesHideSphere(f, &tiles, {21, 40.5f, -14, 1.8f}, HEXLOD_OCCLUSION_MAX_TILES));
}

TEST(OcclusionTests, BoxesTheTestCannotJudgeAreNeverHidden) {
    const shared::CullFrame f = frame();
    const std::vector<float> tiles = wallAt(10.0);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    EXPECT_FALSE(tilesHideBox(f, nullptr, {-1, 20, -1}, {1, 22, 1}));                  // no tiles
    EXPECT_FALSE(tilesHideBox(shared::CullFrame{}, &tiles, {-1, 20, -1}, {1, 22, 1})); // occlusion off
    EXPECT_FALSE(tilesHideBox(f, &tiles, {1, 22, 1}, {-1, 20, -1}));                   // empty
    EXPECT_FALSE(tilesHideBox(f, &tiles, {-1, 0.1f, -1}, {1, 22, 1})); // reaches the near plane
    EXPECT_FALSE(tilesHideBox(f, &tiles, {-1, -30, -1}, {1, -20, 1})); // behind the camera
    EXPECT_FALSE(tilesHideBox(f, &tiles, {nan, 20, -1}, {1, 22, 1}));
    EXPECT_FALSE(tilesHideBox(f, &tiles, {-1, 20, -1}, {inf, 22, 1}));
    // Huge or far out but finite, and behind the wall: hidden (the test works in double).
    EXPECT_TRUE(tilesHideBox(f, &tiles, {-1e30f, 20, -1e30f}, {1e30f, 1e30f, 1e30f}));
    EXPECT_TRUE(tilesHideBox(f, &tiles, {-1, 4000, -1}, {1, 4001, 1}));
}

} // namespace
} // namespace hexlod::lod
