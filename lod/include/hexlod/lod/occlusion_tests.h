// The CPU side of the occlusion test against DepthTiles: whether the tiles of what the frame
// has drawn so far hide a bounding volume. The cull pass's own test (occlusionRect in
// cull_shared.h) runs on the GPU per terminal; these run per page of terminals, per chunk of
// trees and per batch of base volumes, before any of their work is submitted.
#pragma once

#include "hexlod/lod/cull_shared.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace hexlod::lod {

// Whether `tiles` (row by row from the bottom, as DepthTiles::read; null: none) hide a
// camera-relative sphere (xyz, radius) that covers at most `maxTiles` tiles: the test
// terminal_cull.comp makes per terminal, with the same rounding.
bool tilesHideSphere(const shared::CullFrame& frame, const std::vector<float>* tiles, const glm::vec4& sphere,
                     uint32_t maxTiles);

// Tiles read back for the box test, with blocks over them: each block the farthest depth of
// the kOcclusionBlock x kOcclusionBlock tiles under it (fewer at the grid's far edges). A
// block nearer than a box settles all its tiles at once, so a large rectangle costs about
// as many lookups as at tiles that many times larger, and small tiles only where a block
// may show the box.
constexpr uint32_t kOcclusionBlock = 4;
struct OcclusionGrid {
    std::vector<float> tiles; // row by row from the bottom, as DepthTiles::read
    uint32_t columns = 0, rows = 0;
    std::vector<float> blocks; // likewise
    uint32_t blockColumns = 0, blockRows = 0;
};
// The grid over `tiles` (columns x rows); empty when their count does not match.
OcclusionGrid occlusionGrid(std::vector<float> tiles, uint32_t columns, uint32_t rows);

// Whether the grid's tiles (null: none) hide a camera-relative axis-aligned box [boxMin,
// boxMax]: every tile its eight corners' screen rectangle covers holds depth nearer than the
// box's nearest corner. `frame.occlusion` must describe the grid's tiles. A box that reaches
// the near plane, or is empty or not finite, is never hidden. A city's batches are wide and
// low, so a box fits them far tighter than a sphere.
bool tilesHideBox(const shared::CullFrame& frame, const OcclusionGrid* grid, const glm::vec3& boxMin,
                  const glm::vec3& boxMax);

} // namespace hexlod::lod
