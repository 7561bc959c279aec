// LOD0's far form: which buildings are points, and what a point carries.
#include "hexlod/lod/building_points.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hexlod::lod {
namespace {

// A building 30 x 40 m across and 120 m tall (its box's diagonal 130 m), at the mesh's origin.
render::VolumeBuilding tower() {
    render::VolumeBuilding b;
    b.boundsMin = glm::vec3(0.0f);
    b.boundsMax = glm::vec3(30.0f, 40.0f, 120.0f);
    b.footprintArea = 1200.0f;
    b.footprintPerimeter = 140.0f;
    b.wallColour = 0x11223344u;
    return b;
}

TEST(BuildingPoints, APointCarriesTheBoxCentreTheHeightTheFootprintAndBothColours) {
    const std::vector<GpuBuildingPoint> points = packBuildingPoints({tower(), render::VolumeBuilding{}});
    ASSERT_EQ(points.size(), 2u);
    EXPECT_EQ(points[0].centreHeight, glm::vec4(15.0f, 20.0f, 60.0f, 120.0f));
    EXPECT_EQ(points[0].footprintArea, 1200.0f);
    EXPECT_EQ(points[0].footprintPerimeter, 140.0f);
    EXPECT_EQ(points[0].wallColour, 0x11223344u);
    EXPECT_EQ(points[0].roofColour, render::roofColour());
    EXPECT_EQ(points[1].centreHeight, glm::vec4(0.0f));
    EXPECT_TRUE(packBuildingPoints({}).empty());
}

TEST(BuildingPoints, ABuildingIsAPointWhileItsBoxIsSmallerOnScreenThanThePointDiameter) {
    const render::VolumeBuilding b = tower();
    // 1000 px a metre at a metre, points under 4 px: the 130 m diagonal is 4 px at 32.5 km.
    const BuildingPointCut cut{1000.0f, 4.0f};
    const glm::vec3 centre(15.0f, 20.0f, 60.0f);
    const auto at = [&](float distance) { return glm::vec3(distance, 0.0f, 0.0f) - centre; };
    EXPECT_FALSE(buildingIsPoint(b, at(30000.0f), cut));
    EXPECT_TRUE(buildingIsPoint(b, at(35000.0f), cut));
    // The camera inside the box, or at its centre, never sees a point.
    EXPECT_FALSE(buildingIsPoint(b, -centre, cut));
    EXPECT_FALSE(buildingIsPoint(b, glm::vec3(-5.0f), cut));
    // A cut of 0 (or NaN) makes no point, however far.
    EXPECT_FALSE(buildingIsPoint(b, at(1e7f), BuildingPointCut{1000.0f, 0.0f}));
    EXPECT_FALSE(buildingIsPoint(b, at(1e7f), BuildingPointCut{1000.0f, std::nanf("")}));
}

} // namespace
} // namespace hexlod::lod
