#include "hexlod/lod/building_points.h"

#include <glm/geometric.hpp>

namespace hexlod::lod {

std::vector<GpuBuildingPoint> packBuildingPoints(const std::vector<render::VolumeBuilding>& buildings) {
    std::vector<GpuBuildingPoint> points;
    points.reserve(buildings.size());
    for (const render::VolumeBuilding& b : buildings) {
        GpuBuildingPoint p;
        p.centreHeight = glm::vec4(0.5f * (b.boundsMin + b.boundsMax), b.boundsMax.z - b.boundsMin.z);
        p.footprintArea = b.footprintArea;
        p.footprintPerimeter = b.footprintPerimeter;
        p.wallColour = b.wallColour;
        p.roofColour = render::roofColour();
        points.push_back(p);
    }
    return points;
}

bool buildingIsPoint(const render::VolumeBuilding& building, const glm::vec3& origin,
                     const BuildingPointCut& cut) {
    if (!(cut.pointDiameter > 0.0f)) return false;
    const glm::vec3 centre = origin + 0.5f * (building.boundsMin + building.boundsMax);
    const float diameter = glm::length(building.boundsMax - building.boundsMin);
    // diameter / distance < limit, without the division (a building around the camera is not).
    return diameter * cut.screenScale < cut.pointDiameter * glm::length(centre);
}

} // namespace hexlod::lod
