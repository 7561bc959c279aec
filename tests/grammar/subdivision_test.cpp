#include "hexlod/grammar/subdivision.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace hexlod::grammar {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(SplitSizes, RelativeWeightsShareTheRemainder) {
    const float sizes[] = {1, 2, 1};
    const bool relative[] = {false, true, true};
    float parts[3];
    EXPECT_EQ(splitSizes(10, sizes, relative, 3, parts), SubdivisionStatus::Ok);
    EXPECT_FLOAT_EQ(parts[0], 1);
    EXPECT_FLOAT_EQ(parts[1], 6);
    EXPECT_FLOAT_EQ(parts[2], 3);
}

TEST(SplitSizes, RelativeWeightsSummingToZeroGetNothing) {
    const float sizes[] = {4, 0, 0};
    const bool relative[] = {false, true, true};
    float parts[3];
    EXPECT_EQ(splitSizes(10, sizes, relative, 3, parts), SubdivisionStatus::Ok);
    EXPECT_FLOAT_EQ(parts[0], 4);
    EXPECT_FLOAT_EQ(parts[1], 0);
    EXPECT_FLOAT_EQ(parts[2], 0);
}

TEST(SplitSizes, InvalidSizesCountAsZeroAndAreReported) {
    const float sizes[] = {kNaN, -3, kInf, 2};
    const bool relative[] = {false, false, false, true};
    float parts[4];
    EXPECT_EQ(splitSizes(10, sizes, relative, 4, parts), SubdivisionStatus::InvalidSize);
    EXPECT_FLOAT_EQ(parts[0], 0);
    EXPECT_FLOAT_EQ(parts[1], 0);
    EXPECT_FLOAT_EQ(parts[2], 0);
    EXPECT_FLOAT_EQ(parts[3], 10);
}

TEST(SplitSizes, PartsNeverExceedTheScope) {
    const float sizes[] = {1e30f, 1e30f};
    const bool relative[] = {false, false};
    float parts[2];
    EXPECT_EQ(splitSizes(10, sizes, relative, 2, parts), SubdivisionStatus::Ok);
    EXPECT_NEAR(parts[0] + parts[1], 10.0f, 1e-4f);
}

TEST(SplitSizes, NegativeOrZeroScopeGivesEmptyParts) {
    const float sizes[] = {1, 1};
    const bool relative[] = {false, true};
    float parts[2];
    splitSizes(-5, sizes, relative, 2, parts);
    EXPECT_FLOAT_EQ(parts[0], 0);
    EXPECT_FLOAT_EQ(parts[1], 0);
}

TEST(RepeatLayout, FitAndEqualOnTheSameScope) {
    RepeatLayout layout;
    ASSERT_EQ(repeatLayout(10, 3, RepeatMode::Fit, 1000, layout), SubdivisionStatus::Ok);
    EXPECT_EQ(layout.tiles, 3u);
    EXPECT_FLOAT_EQ(layout.tileSize, 3);
    EXPECT_FLOAT_EQ(layout.margin, 0.5f);
    ASSERT_EQ(repeatLayout(10, 3, RepeatMode::Equal, 1000, layout), SubdivisionStatus::Ok);
    EXPECT_EQ(layout.tiles, 3u);
    EXPECT_FLOAT_EQ(layout.tileSize, 10.0f / 3.0f);
    EXPECT_FLOAT_EQ(layout.margin, 0);
}

TEST(RepeatLayout, TileLargerThanTheScope) {
    RepeatLayout layout;
    ASSERT_EQ(repeatLayout(2, 5, RepeatMode::Fit, 1000, layout), SubdivisionStatus::Ok);
    EXPECT_EQ(layout.tiles, 0u);
    EXPECT_FLOAT_EQ(layout.margin, 1);
    ASSERT_EQ(repeatLayout(2, 5, RepeatMode::Equal, 1000, layout), SubdivisionStatus::Ok);
    EXPECT_EQ(layout.tiles, 1u);
    EXPECT_FLOAT_EQ(layout.tileSize, 2);
}

TEST(RepeatLayout, FloatRoundOffDoesNotLoseATile) {
    RepeatLayout layout;
    const float length = 0.1f * 30.0f; // 3.0000001 or 2.9999998 depending on rounding
    ASSERT_EQ(repeatLayout(length, 1.0f, RepeatMode::Fit, 1000, layout), SubdivisionStatus::Ok);
    EXPECT_EQ(layout.tiles, 3u);
    EXPECT_GE(layout.margin, 0.0f);
}

TEST(RepeatLayout, InvalidTileSizes) {
    RepeatLayout layout;
    for (float size : {0.0f, -1.0f, kNaN, kInf, -kInf}) {
        EXPECT_EQ(repeatLayout(10, size, RepeatMode::Equal, 1000, layout), SubdivisionStatus::InvalidSize)
            << size;
        EXPECT_EQ(layout.tiles, 0u);
    }
}

TEST(RepeatLayout, TinyTilesHitTheCapInsteadOfLooping) {
    RepeatLayout layout;
    EXPECT_EQ(repeatLayout(10, 1e-30f, RepeatMode::Fit, 1u << 20, layout), SubdivisionStatus::TooManyTiles);
    EXPECT_EQ(layout.tiles, 0u);
    EXPECT_EQ(repeatLayout(1e4f, 1e-2f, RepeatMode::Equal, 1u << 20, layout), SubdivisionStatus::Ok);
    EXPECT_EQ(layout.tiles, 1000000u);
}

} // namespace
} // namespace hexlod::grammar
