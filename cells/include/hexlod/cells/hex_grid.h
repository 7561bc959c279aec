// The hexagonal grid the city is clustered into: pointy-top hexagons in axial coordinates
// (q, r), after Red Blob Games, "Hexagonal Grids" (https://www.redblobgames.com/grids/hexagons/),
// with cube rounding for point location and the ring/spiral walks of that page.
//
// World frame: doubles, x east, y north (z up; the grid is 2D). Red Blob's formulas are used as
// they are, so with y pointing north the +r axis points north-north-east and the corner list runs
// counter-clockwise. Every computation first subtracts the grid origin in double, so a city
// 1e7 m from the world origin locates its cells exactly as one at the origin does.
#pragma once

#include <glm/vec2.hpp>

#include <array>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace hexlod::cells {

class Frustum;

// Cells are only meaningful while |q|, |r| and |s| stay within this bound; queries that would
// produce cells beyond it throw std::out_of_range. Arithmetic on coordinates runs in 64 bits, so
// stepping past it (neighbours of an extreme cell) wraps instead of being undefined.
inline constexpr int32_t kMaxCoordinate = int32_t{1} << 30;

// Region queries (rings, spirals, rectangles, polygons, frusta) throw std::length_error rather
// than examine more candidate cells than this; an absurd rectangle must not allocate billions.
inline constexpr std::size_t kMaxQueryCells = std::size_t{1} << 22;

struct HexCoord {
    int32_t q = 0;
    int32_t r = 0;

    // The third cube coordinate; q + r + s == 0.
    constexpr int32_t s() const { return static_cast<int32_t>(-int64_t{q} - r); }

    friend constexpr bool operator==(HexCoord, HexCoord) = default;
    // Lexicographic by (q, r): the order every region query returns its cells in.
    friend constexpr auto operator<=>(HexCoord, HexCoord) = default;
};

struct HexCoordHash {
    std::size_t operator()(HexCoord c) const noexcept;
};

// Axial direction vectors in counter-clockwise order starting east: E, NE, NW, W, SW, SE.
// Neighbour i lies across the edge from corners()[i] to corners()[(i + 1) % 6].
inline constexpr std::array<HexCoord, 6> kHexDirections = {
    {{1, 0}, {0, 1}, {-1, 1}, {-1, 0}, {0, -1}, {1, -1}}};

std::array<HexCoord, 6> neighbours(HexCoord c);

// Number of steps between two cells (cube distance).
int64_t distance(HexCoord a, HexCoord b);

// The 6 * radius cells at exactly `radius` steps, starting at center + radius * SW and walking
// E, NE, NW, W, SW, SE (Red Blob's ring walk). Radius 0 gives {center}. Throws
// std::invalid_argument for a negative radius, std::length_error beyond kMaxQueryCells.
std::vector<HexCoord> ring(HexCoord center, int32_t radius);

// The 3 * radius * (radius + 1) + 1 cells within `radius` steps: the centre, then ring 1, ring 2...
// Same errors as ring().
std::vector<HexCoord> spiral(HexCoord center, int32_t radius);

class HexGrid {
public:
    // circumradius: centre-to-corner distance in metres (finite, > 0). origin: the world
    // position of cell (0, 0)'s centre (finite). Throws std::invalid_argument naming the argument.
    explicit HexGrid(double circumradius, glm::dvec2 origin = {0.0, 0.0});

    double circumradius() const { return size_; }
    double inradius() const { return width_ * 0.5; } // centre to edge midpoint
    glm::dvec2 origin() const { return origin_; }

    // The cell whose hexagon holds `world`, by cube rounding relative to the origin. A point the
    // arithmetic puts exactly on a shared edge or corner is decided by cube rounding itself:
    // components round half up, and when two rounding errors are equal s is recomputed before
    // r before q. So the top corner (0, size) of cell (0, 0) belongs to (0, 1) and its bottom
    // corner (0, -size) to (0, -1). Throws std::invalid_argument for a non-finite point and
    // std::out_of_range beyond kMaxCoordinate.
    HexCoord cellOf(glm::dvec2 world) const;

    glm::dvec2 center(HexCoord c) const { return origin_ + localCenter(c); }
    // Centre relative to the grid origin: exact where world positions are not (far cities).
    glm::dvec2 localCenter(HexCoord c) const;
    // Counter-clockwise from the lower-right corner (angle -30 degrees), as Red Blob's
    // 60 * i - 30 degree formula gives with y north.
    std::array<glm::dvec2, 6> corners(HexCoord c) const;

    // Every cell whose closed hexagon meets the closed rectangle [lo, hi] (the hexagon test is
    // exact, not a test of centres), sorted by (q, r). Throws std::invalid_argument for
    // non-finite corners or lo > hi, std::length_error beyond kMaxQueryCells, std::out_of_range
    // beyond kMaxCoordinate.
    std::vector<HexCoord> cellsInRectangle(glm::dvec2 lo, glm::dvec2 hi) const;

    // Every cell whose closed hexagon meets the convex polygon `points` (world, either winding;
    // one point or a segment also work), sorted by (q, r). A non-convex input still gets every
    // cell it meets, plus perhaps some that only its convex hull meets. Errors as for
    // cellsInRectangle.
    std::vector<HexCoord> cellsInConvexPolygon(std::span<const glm::dvec2> points) const;

    // Cells whose prism (hexagon x [zMin, zMax]) may intersect the frustum, sorted by (q, r).
    // Conservative: no cell with a visible part is left out. Candidates come from the ground
    // footprint of the frustum clipped to the slab zMin <= z <= zMax, so a far plane 100 km out
    // over a 10 m slab costs what the slab can actually show. Throws std::invalid_argument for
    // non-finite or reversed z bounds, std::length_error beyond kMaxQueryCells.
    std::vector<HexCoord> cellsInFrustum(const Frustum& frustum, double zMin, double zMax) const;

private:
    double size_;  // circumradius
    double width_; // sqrt(3) * size: centre spacing along a row
    glm::dvec2 origin_;
};

} // namespace hexlod::cells

template <> struct std::hash<hexlod::cells::HexCoord> : hexlod::cells::HexCoordHash {};
