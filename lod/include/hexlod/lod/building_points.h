// LOD0's far form: a building whose box is a few pixels across on screen shows no more than a
// blend of its roof and walls, so LOD0 draws it as one point of that colour and of the area
// it projects to (shaders/building_point.vert) instead of its shell's triangles. llvmpipe's
// cost is per triangle, and in the thesis city's overview a hundred thousand shells of about
// sixteen triangles each are two or three pixels across (docs/BENCHMARKS.md, "The overview:
// far base volumes in the mesh's order, far buildings as points"). The rule is the trees'
// (TreeFrame::pointDiameter): a building is a point while its box's bounding sphere is smaller
// on screen than a multiple of the error bound.
#pragma once

#include "hexlod/render/base_volume_mesh.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace hexlod::lod {

// One building's point, as building_point.vert reads it (std430, 32 bytes).
struct GpuBuildingPoint {
    glm::vec4 centreHeight;     // xyz: its box's centre, cell-local metres; w: its height
    float footprintArea = 0.0f; // of its lowest band, square metres
    float footprintPerimeter = 0.0f;
    uint32_t wallColour = 0, roofColour = 0; // rgba8
};
static_assert(sizeof(GpuBuildingPoint) == 32, "read as a std430 array of 32-byte structs");

// A mesh's buildings (render::buildBaseVolumes) as points, in the same order.
std::vector<GpuBuildingPoint> packBuildingPoints(const std::vector<render::VolumeBuilding>& buildings);

// When a building is a point: `screenScale` pixels one metre spans at one metre's distance,
// `pointDiameter` the pixels under which its box's bounding sphere must stay (0: never).
struct BuildingPointCut {
    float screenScale = 0.0f;
    float pointDiameter = 0.0f;
};

// Whether `building`, of a mesh whose origin lies at `origin` relative to the camera, is drawn
// as a point under `cut`.
bool buildingIsPoint(const render::VolumeBuilding& building, const glm::vec3& origin,
                     const BuildingPointCut& cut);

} // namespace hexlod::lod
