// The order in which a base volume mesh's buildings are drawn: nearest the camera first. At
// one sample llvmpipe tests depth before it shades and skips a group of pixels that all fail,
// so a near building drawn first spares the shading of the ones it hides (the shells under
// terminal sets are drawn before anything else, with no depth to be tested against). Far
// away that saves little, and each run costs llvmpipe a draw of its own: there the buildings
// keep the mesh's order, in as few runs as the ones left out allow.
#pragma once

#include "hexlod/render/base_volume_mesh.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace hexlod::lod {

// The index runs (first index, count) of `kept` (indices into `buildings`), nearest first by
// the distance from the camera to each building's box, `origin` being the mesh's origin
// relative to the camera. Ties keep the order of `kept`; buildings adjacent in both the order
// and the index buffer share a run, so an unmoved camera inside one row costs few draws.
std::vector<glm::uvec2> nearestFirstRuns(const std::vector<render::VolumeBuilding>& buildings,
                                         const std::vector<uint32_t>& kept, const glm::vec3& origin);

// The index runs of `kept` (indices into `buildings`) in the order given, buildings adjacent
// in both that order and the index buffer sharing a run.
std::vector<glm::uvec2> buildingRuns(const std::vector<render::VolumeBuilding>& buildings,
                                     const std::vector<uint32_t>& kept);

// Appends the run (first, count) to `runs`, extending the last run where it ends at `first`.
void appendRun(std::vector<glm::uvec2>& runs, uint32_t first, uint32_t count);

} // namespace hexlod::lod
