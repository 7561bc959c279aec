// The CPU occlusion tests against hand-made tiles: a wall 10 m ahead covers the whole view,
// or stops at a roofline.
#include "hexlod/lod/cull_inputs.h"
#include "hexlod/lod/occlusion_tests.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
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

OcclusionGrid wallAt(double d) {
    return occlusionGrid(std::vector<float>(kColumns * kRows, depthAt(d)), kColumns, kRows);
}

TEST(OcclusionTests, ABoxBehindTheWallIsHiddenAndOneBeforeItIsNot) {
    const shared::CullFrame f = frame();
    const OcclusionGrid tiles = wallAt(10.0);
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
    std::vector<float> wall(kColumns * kRows, depthAt(10.0));
    wall[kColumns - 1] = 0.0f; // the bottom right tile: sky
    const OcclusionGrid tiles = occlusionGrid(wall, kColumns, kRows);
    // A small box at the centre covers the four middle tiles only.
    EXPECT_TRUE(tilesHideBox(f, &tiles, {-0.5f, 40, -0.5f}, {0.5f, 41, 0.5f}));
    // One far to the right and below covers the gap.
    EXPECT_FALSE(tilesHideBox(f, &tiles, {20, 40, -15}, {22, 41, -13}));
    // The sphere test agrees on both.
    EXPECT_TRUE(tilesHideSphere(f, &wall, {0, 40.5f, 0, 0.9f}, HEXLOD_OCCLUSION_MAX_TILES));
    EXPECT_FALSE(tilesHideSphere(f, &wall, {21, 40.5f, -14, 1.8f}, HEXLOD_OCCLUSION_MAX_TILES));
}

TEST(OcclusionTests, BoxesTheTestCannotJudgeAreNeverHidden) {
    const shared::CullFrame f = frame();
    const OcclusionGrid tiles = wallAt(10.0);
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

// The farthest depth of each `size`-pixel tile of a width x height depth image.
OcclusionGrid tilesOf(const std::vector<float>& depths, uint32_t width, uint32_t height, uint32_t size) {
    const uint32_t columns = (width + size - 1) / size, rows = (height + size - 1) / size;
    std::vector<float> tiles(size_t(columns) * rows, 1.0f);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            float& tile = tiles[size_t(y / size) * columns + x / size];
            tile = std::min(tile, depths[size_t(y) * width + x]);
        }
    return occlusionGrid(std::move(tiles), columns, rows);
}

TEST(OcclusionTests, FinerTilesHideWhatARooflineTileCannot) {
    // 64 x 32 pixels: a wall 10 m ahead up to row 22 from the bottom, sky above it.
    constexpr uint32_t width = 64, height = 32;
    std::vector<float> depths(size_t(width) * height, 0.0f);
    for (uint32_t y = 0; y < 22; ++y)
        for (uint32_t x = 0; x < width; ++x) depths[size_t(y) * width + x] = depthAt(10.0);
    // A box 40 m ahead whose image (rows 14.6 to 17.4) lies below the roofline, but in the
    // 16-pixel tiles whose upper half is sky.
    const glm::vec3 lo(-1, 40, -2), hi(1, 41, 2);
    shared::CullFrame coarse{}, fine{};
    setOcclusion(coarse, {0, 1, 0}, {0, 0, 1}, 60.0 * M_PI / 180.0, kNear, kFar, width, height, 4, 2, 16);
    setOcclusion(fine, {0, 1, 0}, {0, 0, 1}, 60.0 * M_PI / 180.0, kNear, kFar, width, height, 16, 8, 4);
    const OcclusionGrid coarseTiles = tilesOf(depths, width, height, 16);
    const OcclusionGrid fineTiles = tilesOf(depths, width, height, 4);
    EXPECT_FALSE(tilesHideBox(coarse, &coarseTiles, lo, hi));
    EXPECT_TRUE(tilesHideBox(fine, &fineTiles, lo, hi));
    // Raised into the sky, it shows in both.
    EXPECT_FALSE(tilesHideBox(fine, &fineTiles, lo + glm::vec3(0, 0, 8), hi + glm::vec3(0, 0, 8)));
    // A frame that describes other tiles than the grid's tests nothing.
    EXPECT_FALSE(tilesHideBox(coarse, &fineTiles, lo, hi));
}

TEST(OcclusionTests, TheBlocksAnswerAsTheTilesAlone) {
    // 1280 x 720 pixels in 4-pixel tiles: walls at random depths with holes of sky, and boxes
    // of every size; the same grid with every block "may show" checks each tile itself.
    constexpr uint32_t columns = 320, rows = 180;
    std::mt19937 random(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> tiles(size_t(columns) * rows);
    for (float& tile : tiles) tile = unit(random) < 0.002f ? 0.0f : depthAt(8.0 + 4.0 * unit(random));
    const OcclusionGrid grid = occlusionGrid(tiles, columns, rows);
    ASSERT_EQ(grid.blockColumns, 80u);
    ASSERT_EQ(grid.blockRows, 45u);
    OcclusionGrid tileByTile = grid;
    std::fill(tileByTile.blocks.begin(), tileByTile.blocks.end(), 0.0f);
    shared::CullFrame f{};
    setOcclusion(f, {0, 1, 0}, {0, 0, 1}, 60.0 * M_PI / 180.0, kNear, kFar, 1280, 720, columns, rows, 4);
    int hidden = 0, shown = 0;
    for (int i = 0; i < 4000; ++i) {
        const glm::vec3 centre(60.0f * (unit(random) - 0.5f), 12.0f + 40.0f * unit(random),
                               30.0f * (unit(random) - 0.5f));
        const glm::vec3 half =
            glm::vec3(unit(random), unit(random), unit(random)) * (0.2f + 10.0f * unit(random));
        const bool answer = tilesHideBox(f, &grid, centre - half, centre + half);
        ASSERT_EQ(answer, tilesHideBox(f, &tileByTile, centre - half, centre + half)) << i;
        ++(answer ? hidden : shown);
    }
    // Both answers are common, so the comparison means something.
    EXPECT_GT(hidden, 400);
    EXPECT_GT(shown, 400);
}

TEST(OcclusionTests, AGridOfTheWrongSizeIsEmpty) {
    EXPECT_TRUE(occlusionGrid(std::vector<float>(7, 0.5f), 4, 2).tiles.empty());
    EXPECT_TRUE(occlusionGrid({}, 0, 0).tiles.empty());
    const OcclusionGrid odd = occlusionGrid(std::vector<float>(5 * 3, 0.5f), 5, 3);
    EXPECT_EQ(odd.blockColumns, 2u);
    EXPECT_EQ(odd.blockRows, 1u);
}

} // namespace
} // namespace hexlod::lod
