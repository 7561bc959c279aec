#include "hexlod/grammar/footprint.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace hexlod::grammar {
namespace {

TEST(Footprint, ClockwiseIsReversedToCounterClockwise) {
    CleanFootprint clean;
    std::string error;
    ASSERT_TRUE(cleanFootprint({{0, 0}, {0, 5}, {10, 5}, {10, 0}}, clean, error)) << error;
    EXPECT_TRUE(clean.reversed);
    EXPECT_DOUBLE_EQ(clean.area, 50.0);
    EXPECT_EQ(clean.points.size(), 4u);
}

TEST(Footprint, DuplicateClosingAndCollinearPointsAreRemoved) {
    CleanFootprint clean;
    std::string error;
    ASSERT_TRUE(cleanFootprint({{0, 0}, {5, 0}, {5, 0}, {10, 0}, {10, 5}, {0, 5}, {0, 0}}, clean, error))
        << error;
    EXPECT_EQ(clean.points.size(), 4u);
    EXPECT_EQ(clean.removedPoints, 3u);
    EXPECT_FALSE(clean.reversed);
}

TEST(Footprint, SpikesAreRemoved) {
    // (10, 8) doubles back along the edge to (10, 5): a zero-width spike.
    CleanFootprint clean;
    std::string error;
    ASSERT_TRUE(cleanFootprint({{0, 0}, {10, 0}, {10, 8}, {10, 5}, {0, 5}}, clean, error)) << error;
    EXPECT_EQ(clean.points.size(), 4u);
    EXPECT_DOUBLE_EQ(clean.area, 50.0);
}

TEST(Footprint, DegenerateInputsAreRejectedWithAReason) {
    CleanFootprint clean;
    std::string error;
    EXPECT_FALSE(cleanFootprint({}, clean, error));
    EXPECT_FALSE(cleanFootprint({{1, 1}, {1, 1}, {1, 1}}, clean, error));
    EXPECT_NE(error.find("fewer than 3"), std::string::npos);
    EXPECT_FALSE(cleanFootprint({{0, 0}, {1, 1}, {2, 2}, {3, 3}}, clean, error));
    EXPECT_NE(error.find("fewer than 3"), std::string::npos);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(cleanFootprint({{0, 0}, {1, 0}, {nan, 1}}, clean, error));
    EXPECT_NE(error.find("non-finite"), std::string::npos);
}

TEST(Footprint, BowTieIsKeptAndFlagged) {
    CleanFootprint clean;
    std::string error;
    ASSERT_TRUE(cleanFootprint({{0, 0}, {10, 0}, {10, 10}, {4, -3}}, clean, error)) << error;
    EXPECT_TRUE(clean.selfIntersecting);
}

TEST(Footprint, FarFromTheOriginAndTiny) {
    CleanFootprint clean;
    std::string error;
    const double far = 1e7;
    ASSERT_TRUE(
        cleanFootprint({{far, far}, {far + 20, far}, {far + 20, far + 12}, {far, far + 12}}, clean, error));
    EXPECT_NEAR(clean.area, 240.0, 1e-6);
    // A 5 mm x 5 mm footprint (25 mm^2) is still a footprint.
    ASSERT_TRUE(cleanFootprint({{0, 0}, {0.005, 0}, {0.005, 0.005}, {0, 0.005}}, clean, error)) << error;
    EXPECT_EQ(clean.points.size(), 4u);
}

} // namespace
} // namespace hexlod::grammar
