// The order of a base volume mesh's buildings: nearest the camera first, or the mesh's own far
// away; adjacent ones merged.
#include "hexlod/lod/building_order.h"

#include <gtest/gtest.h>

#include <vector>

namespace hexlod::lod {
namespace {

// Buildings of 6 indices each along +x, 10 m apart, from x = 0, as a mesh lays them out.
std::vector<render::VolumeBuilding> row(uint32_t count) {
    std::vector<render::VolumeBuilding> buildings;
    for (uint32_t i = 0; i < count; ++i)
        buildings.push_back({i * 6, 6, glm::vec3(10.0f * i, 0, 0), glm::vec3(10.0f * i + 5, 5, 5)});
    return buildings;
}

using Runs = std::vector<glm::uvec2>;

TEST(BuildingOrderTest, TheNearestBuildingsComeFirstAndNeighboursInBothOrdersShareARun) {
    const auto buildings = row(4);
    // The camera at x = 100: building 3 nearest; descending index order never adjoins.
    EXPECT_EQ(nearestFirstRuns(buildings, {0, 1, 2, 3}, glm::vec3(-100, -1, 0)),
              (Runs{{18, 6}, {12, 6}, {6, 6}, {0, 6}}));
    // At x = -100 the index order is the distance order: one run.
    EXPECT_EQ(nearestFirstRuns(buildings, {0, 1, 2, 3}, glm::vec3(100, -1, 0)), (Runs{{0, 24}}));
    // Only the buildings kept; the gap left by building 1 splits the run.
    EXPECT_EQ(nearestFirstRuns(buildings, {0, 2, 3}, glm::vec3(100, -1, 0)), (Runs{{0, 6}, {12, 12}}));
    EXPECT_TRUE(nearestFirstRuns(buildings, {}, glm::vec3(0.0f)).empty());
}

TEST(BuildingOrderTest, TheBoxNotItsCornerDecidesAndACameraInsideABuildingDrawsItFirst) {
    // A long building (index 0) whose box the camera stands beside, a small one (index 1) whose
    // corner is nearer than the long one's far corners.
    std::vector<render::VolumeBuilding> buildings = {{0, 6, glm::vec3(-50, 10, 0), glm::vec3(50, 20, 30)},
                                                     {6, 6, glm::vec3(3, -8, 0), glm::vec3(6, -5, 3)}};
    EXPECT_EQ(nearestFirstRuns(buildings, {1, 0}, glm::vec3(0.0f)), (Runs{{6, 6}, {0, 6}}));
    // The camera inside building 0 (its box is at distance 0).
    EXPECT_EQ(nearestFirstRuns(buildings, {1, 0}, glm::vec3(0, -15, -10)), (Runs{{0, 12}}));
    // Equal distances keep the order given.
    std::vector<render::VolumeBuilding> twins = {{0, 6, glm::vec3(5, -1, 0), glm::vec3(6, 1, 1)},
                                                 {6, 6, glm::vec3(-6, -1, 0), glm::vec3(-5, 1, 1)}};
    EXPECT_EQ(nearestFirstRuns(twins, {1, 0}, glm::vec3(0.0f)), (Runs{{6, 6}, {0, 6}}));
    EXPECT_EQ(nearestFirstRuns(twins, {0, 1}, glm::vec3(0.0f)), (Runs{{0, 12}}));
}

TEST(BuildingOrderTest, FarBuildingsKeepTheGivenOrderInAsFewRunsAsTheGapsAllow) {
    const auto buildings = row(5);
    EXPECT_EQ(buildingRuns(buildings, {0, 1, 2, 3, 4}), (Runs{{0, 30}}));
    // Buildings 2 and 4 left out: two runs of what is left, in the mesh's order.
    EXPECT_EQ(buildingRuns(buildings, {0, 1, 3}), (Runs{{0, 12}, {18, 6}}));
    // An order against the mesh's shares no run.
    EXPECT_EQ(buildingRuns(buildings, {1, 0}), (Runs{{6, 6}, {0, 6}}));
    EXPECT_TRUE(buildingRuns(buildings, {}).empty());
}

} // namespace
} // namespace hexlod::lod
