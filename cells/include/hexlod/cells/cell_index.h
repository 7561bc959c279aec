// The cell index: which hexagonal cell every building and tree of a scene belongs to, each
// occupied cell's bounds, and the (cell, grammar) batches that terminal sets are generated
// and cached for (ARCHITECTURE.md §4, "Cells").
//
// Assignment: a building belongs to the cell holding its footprint's area centroid. The
// centroid is computed in double relative to the footprint's first vertex, so it is as exact
// for a city 1e7 m out as at the origin; a degenerate footprint (zero area: collinear or
// repeated points) falls back to the mean of its vertices. Trees are footprints too and are
// assigned the same way.
//
// Bounds are an estimate made before expansion, when buildings have no height yet:
// - horizontally, the cell's hexagon grown by every member's footprint bounding box, widened
//   by kFacadeMargin for buildings (balconies, canopies and cornices stand out of the wall)
//   or by half the estimated height for grammars without storeys (a tree crown spreads
//   about as wide as it is tall);
// - vertically, from the lowest base elevation to the highest base elevation plus estimated
//   height. For a grammar that declares `floors` and `floor_h` the estimate is
//   floors × floor_h plus every other parameter whose name ends in `_h` (lobby, cornice,
//   crown and spire heights add to the storeys; the ones inside a storey make the estimate
//   only more generous). Any other grammar (trees, say) is given kDefaultHeight.
// The exact extents come with a batch's terminal set; these bounds only need to keep a
// visible cell from being culled.
#pragma once

#include "hexlod/cells/hex_grid.h"
#include "hexlod/scene/scene_builder.h"

#include <glm/vec2.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace hexlod::cells {

// Height given to members of a grammar without `floors` and `floor_h` (the shipped tree
// species stay under 20 m).
inline constexpr double kDefaultHeight = 30.0;
// How far a building's facade elements may stand out of its footprint, metres.
inline constexpr double kFacadeMargin = 3.0;

struct CellBounds {
    HexCoord cell;
    glm::dvec2 lo{0.0}, hi{0.0}; // world x, y
    double zMin = 0.0, zMax = 0.0;
};

// The buildings of one cell that share one grammar: the unit of generation and caching.
struct Batch {
    HexCoord cell;
    uint32_t grammar = 0;            // the scene's building grammars, then its tree grammars
    std::vector<uint32_t> buildings; // ascending indices into that grammar's building list
};

class CellIndex {
public:
    // Indexes every building and tree of `scene` on a grid of circumradius `cellSize` centred
    // on the scene's local origin (0, 0). Throws std::invalid_argument for a bad cell size, an
    // empty footprint or a non-finite point (naming the grammar and building), and
    // std::out_of_range for a footprint beyond the grid's kMaxCoordinate.
    static CellIndex build(const scene::BuiltScene& scene, double cellSize);

    const HexGrid& grid() const { return grid_; }

    // Every cell with at least one building or tree, sorted by (q, r).
    std::span<const CellBounds> cells() const { return cells_; }
    // Sorted by cell, then grammar; only pairs with at least one building.
    std::span<const Batch> batches() const { return batches_; }

    // nullptr for a cell without buildings or trees.
    const CellBounds* boundsOf(HexCoord cell) const;
    // The cell's batches in grammar order; empty for an unoccupied cell.
    std::span<const Batch> batchesOf(HexCoord cell) const;
    // Throws std::out_of_range for an unknown grammar or building index.
    HexCoord cellOfBuilding(uint32_t grammar, uint32_t building) const;

    // Grammar indices at or past this one are tree grammars.
    uint32_t buildingGrammarCount() const { return buildingGrammars_; }
    uint32_t grammarCount() const { return static_cast<uint32_t>(cellOfMember_.size()); }
    bool isTreeGrammar(uint32_t grammar) const { return grammar >= buildingGrammars_; }
    size_t buildingCount() const { return buildings_; }
    size_t treeCount() const { return trees_; }

    // Heap bytes the index holds (capacities, not sizes), plus the object itself.
    size_t memoryBytes() const;

private:
    explicit CellIndex(HexGrid grid) : grid_(grid) {}
    size_t cellPosition(HexCoord cell) const; // cells_.size() when absent

    HexGrid grid_;
    std::vector<CellBounds> cells_;
    std::vector<uint32_t> firstBatch_; // per cell, then one past the end: batchesOf() ranges
    std::vector<Batch> batches_;
    // Per grammar, per building: position of its cell in cells_.
    std::vector<std::vector<uint32_t>> cellOfMember_;
    uint32_t buildingGrammars_ = 0;
    size_t buildings_ = 0, trees_ = 0;
};

// Area centroid of a footprint (either winding, open or closed ring), with the vertex mean
// for a degenerate one. Throws std::invalid_argument for an empty footprint.
glm::dvec2 footprintCentroid(std::span<const glm::dvec2> footprint);

} // namespace hexlod::cells
