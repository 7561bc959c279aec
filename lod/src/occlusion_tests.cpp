// Sphere and box tests against the occlusion tiles, on the CPU.
#include "hexlod/lod/occlusion_tests.h"

#include <algorithm>
#include <cmath>

namespace hexlod::lod {
namespace {

// True when every tile of the rectangle [x0, x1] x [y0, y1] lies nearer than `nearestDepth`
// (reversed-Z: a tile's value is the farthest depth drawn in it; greater is nearer).
bool rectHidden(const std::vector<float>& tiles, uint32_t columns, uint32_t x0, uint32_t y0, uint32_t x1,
                uint32_t y1, float nearestDepth) {
    for (uint32_t y = y0; y <= y1; ++y)
        for (uint32_t x = x0; x <= x1; ++x)
            if (tiles[size_t(y) * columns + x] <= nearestDepth) return false;
    return true;
}

// rectHidden over the grid: block by block, and tile by tile only within a block that may
// show what lies at `nearestDepth`.
bool gridRectHidden(const OcclusionGrid& grid, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1,
                    float nearestDepth) {
    for (uint32_t by = y0 / kOcclusionBlock; by <= y1 / kOcclusionBlock; ++by)
        for (uint32_t bx = x0 / kOcclusionBlock; bx <= x1 / kOcclusionBlock; ++bx) {
            if (grid.blocks[size_t(by) * grid.blockColumns + bx] > nearestDepth) continue;
            const uint32_t tx0 = std::max(x0, bx * kOcclusionBlock);
            const uint32_t tx1 = std::min(x1, bx * kOcclusionBlock + kOcclusionBlock - 1);
            const uint32_t ty0 = std::max(y0, by * kOcclusionBlock);
            const uint32_t ty1 = std::min(y1, by * kOcclusionBlock + kOcclusionBlock - 1);
            if (!rectHidden(grid.tiles, grid.columns, tx0, ty0, tx1, ty1, nearestDepth)) return false;
        }
    return true;
}

} // namespace

OcclusionGrid occlusionGrid(std::vector<float> tiles, uint32_t columns, uint32_t rows) {
    OcclusionGrid grid;
    if (columns == 0 || rows == 0 || tiles.size() != size_t(columns) * rows) return grid;
    grid.columns = columns;
    grid.rows = rows;
    grid.blockColumns = (columns + kOcclusionBlock - 1) / kOcclusionBlock;
    grid.blockRows = (rows + kOcclusionBlock - 1) / kOcclusionBlock;
    grid.blocks.assign(size_t(grid.blockColumns) * grid.blockRows, 1.0f);
    for (uint32_t y = 0; y < rows; ++y)
        for (uint32_t x = 0; x < columns; ++x) {
            float& block = grid.blocks[size_t(y / kOcclusionBlock) * grid.blockColumns + x / kOcclusionBlock];
            block = std::min(block, tiles[size_t(y) * columns + x]);
        }
    grid.tiles = std::move(tiles);
    return grid;
}

bool tilesHideSphere(const shared::CullFrame& frame, const std::vector<float>* tiles, const glm::vec4& sphere,
                     uint32_t maxTiles) {
    glm::uvec4 rect;
    float nearest = 0.0f;
    if (!tiles || !shared::occlusionRect(glm::vec3(sphere), sphere.w, frame, maxTiles, rect, nearest))
        return false;
    return rectHidden(*tiles, uint32_t(frame.occlusion.x), rect.x, rect.y, rect.z, rect.w, nearest);
}

bool tilesHideBox(const shared::CullFrame& frame, const OcclusionGrid* grid, const glm::vec3& boxMin,
                  const glm::vec3& boxMax) {
    if (!grid || grid->tiles.empty() || frame.occlusion.x != float(grid->columns) ||
        frame.occlusion.y != float(grid->rows))
        return false;
    if (!(boxMin.x <= boxMax.x && boxMin.y <= boxMax.y && boxMin.z <= boxMax.z)) return false;
    const glm::dvec3 right(frame.viewRight), up(frame.viewUp), forward(frame.viewForward);
    double nearZ = INFINITY, ndcX0 = INFINITY, ndcX1 = -INFINITY, ndcY0 = INFINITY, ndcY1 = -INFINITY;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p(corner & 1 ? boxMax.x : boxMin.x, corner & 2 ? boxMax.y : boxMin.y,
                           corner & 4 ? boxMax.z : boxMin.z);
        const double z = glm::dot(forward, p);
        // In front of the near plane, the box's image lies within its corners' images.
        if (!(z > double(frame.viewForward.w))) return false;
        const double x = double(frame.viewRight.w) * glm::dot(right, p) / z;
        const double y = double(frame.viewUp.w) * glm::dot(up, p) / z;
        nearZ = std::min(nearZ, z);
        ndcX0 = std::min(ndcX0, x), ndcX1 = std::max(ndcX1, x);
        ndcY0 = std::min(ndcY0, y), ndcY1 = std::max(ndcY1, y);
    }
    // A pixel past the rectangle on each side: a fragment is generated where its sample lies
    // inside, and that pixel may fall in the tile beyond a boundary the edge just misses.
    const double padX = 2.0 / double(frame.depthMap.z), padY = 2.0 / double(frame.depthMap.w);
    const double toTileX = 0.5 * double(frame.depthMap.z) / double(frame.occlusion.z);
    const double toTileY = 0.5 * double(frame.depthMap.w) / double(frame.occlusion.z);
    const double lastX = double(frame.occlusion.x) - 1.0, lastY = double(frame.occlusion.y) - 1.0;
    auto tile = [](double ndc, double toTile, double last) {
        return uint32_t(std::clamp(std::floor((ndc + 1.0) * toTile), 0.0, last));
    };
    if (!std::isfinite(ndcX0 + ndcX1 + ndcY0 + ndcY1 + nearZ)) return false;
    // Nearer than the box by the cull pass's margin: the occluders' rasterised depth and this
    // one are rounded differently.
    const double marginZ = nearZ - 0.01 - 1e-4 * nearZ;
    if (!(marginZ > double(frame.viewForward.w))) return false;
    const float nearestDepth = float(double(frame.depthMap.x) / marginZ - double(frame.depthMap.y));
    return gridRectHidden(*grid, tile(ndcX0 - padX, toTileX, lastX), tile(ndcY0 - padY, toTileY, lastY),
                          tile(ndcX1 + padX, toTileX, lastX), tile(ndcY1 + padY, toTileY, lastY),
                          nearestDepth);
}

} // namespace hexlod::lod
