// Tests of the cell index: centroids, a hand-built scene with hand-computed cells, batches and
// bounds, assignment right beside cell edges far from the origin, and the invariants
// (partition, containment, determinism) on the shipped default scene.
#include "hexlod/cells/cell_index.h"

#include "hexlod/grammar/batch_expander.h"
#include "hexlod/scene/scene_builder.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

namespace hexlod::cells {
namespace {

constexpr double kSqrt3 = 1.7320508075688772935;

using grammar::BuildingInput;
using scene::BuiltScene;
using scene::GrammarBuildings;

GrammarBuildings grammarOf(const std::string& name, const std::string& source) {
    GrammarBuildings g;
    g.name = name;
    grammar::DiagnosticList diagnostics;
    g.grammar = grammar::compileGrammar(source, name + ".grammar", diagnostics);
    EXPECT_FALSE(diagnostics.hasErrors()) << diagnostics.formatAll();
    return g;
}

// Storeys and a roof: heights are floors * floor_h + roof_h.
GrammarBuildings houses() {
    return grammarOf(
        "house", "param floors = 3 in [1, 20];\nparam floor_h = 3 in [2, 5];\n"
                 "param roof_h = 2 in [0, 5];\nLot -> Extrude(floors * floor_h + roof_h) { NULL, NULL };");
}

// No storeys: kDefaultHeight, with a crown of half that around the footprint.
GrammarBuildings trees() {
    return grammarOf("tree", "param trunk_h = 3 in [1, 10];\nTree -> Extrude(trunk_h) { NULL, NULL };");
}

BuildingInput building(uint32_t id, std::vector<glm::dvec2> footprint, double base = 0.0,
                       std::vector<float> parameters = {}) {
    return {id, std::move(footprint), base, std::move(parameters)};
}

std::vector<glm::dvec2> square(glm::dvec2 center, double half) {
    return {center + glm::dvec2(-half, -half), center + glm::dvec2(half, -half),
            center + glm::dvec2(half, half), center + glm::dvec2(-half, half)};
}

bool hexagonContains(const HexGrid& grid, HexCoord cell, glm::dvec2 p, double slack) {
    const std::array<glm::dvec2, 6> corners = grid.corners(cell);
    for (size_t i = 0; i < 6; ++i) {
        const glm::dvec2 a = corners[i], b = corners[(i + 1) % 6];
        const glm::dvec2 edge = b - a;
        if ((edge.x * (p.y - a.y) - edge.y * (p.x - a.x)) / glm::length(edge) < -slack) return false;
    }
    return true;
}

void expectSameIndex(const CellIndex& a, const CellIndex& b) {
    ASSERT_EQ(a.cells().size(), b.cells().size());
    for (size_t i = 0; i < a.cells().size(); ++i) {
        EXPECT_EQ(a.cells()[i].cell, b.cells()[i].cell);
        EXPECT_EQ(a.cells()[i].lo, b.cells()[i].lo);
        EXPECT_EQ(a.cells()[i].hi, b.cells()[i].hi);
        EXPECT_EQ(a.cells()[i].zMin, b.cells()[i].zMin);
        EXPECT_EQ(a.cells()[i].zMax, b.cells()[i].zMax);
    }
    ASSERT_EQ(a.batches().size(), b.batches().size());
    for (size_t i = 0; i < a.batches().size(); ++i) {
        EXPECT_EQ(a.batches()[i].cell, b.batches()[i].cell);
        EXPECT_EQ(a.batches()[i].grammar, b.batches()[i].grammar);
        EXPECT_EQ(a.batches()[i].buildings, b.batches()[i].buildings);
    }
}

TEST(FootprintCentroid, AreaCentroidOfConvexAndConcavePolygons) {
    const glm::dvec2 c = footprintCentroid(square({3.0, -4.0}, 2.0));
    EXPECT_DOUBLE_EQ(c.x, 3.0);
    EXPECT_DOUBLE_EQ(c.y, -4.0);
    // L of a 2x1 bar (centroid (1, 0.5)) and a 1x1 block on its left end (centroid (0.5, 1.5)):
    // area-weighted (2 * (1, 0.5) + (0.5, 1.5)) / 3.
    const std::vector<glm::dvec2> l{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
    const glm::dvec2 lc = footprintCentroid(l);
    EXPECT_NEAR(lc.x, 2.5 / 3.0, 1e-12);
    EXPECT_NEAR(lc.y, 2.5 / 3.0, 1e-12);
    // Clockwise and closed rings give the same point.
    std::vector<glm::dvec2> clockwise(l.rbegin(), l.rend());
    clockwise.push_back(clockwise.front());
    const glm::dvec2 cc = footprintCentroid(clockwise);
    EXPECT_NEAR(cc.x, lc.x, 1e-12);
    EXPECT_NEAR(cc.y, lc.y, 1e-12);
}

TEST(FootprintCentroid, DegenerateFootprintsFallBackToTheVertexMean) {
    const glm::dvec2 line = footprintCentroid(std::vector<glm::dvec2>{{0, 0}, {1, 1}, {4, 4}});
    EXPECT_DOUBLE_EQ(line.x, 5.0 / 3.0);
    EXPECT_DOUBLE_EQ(line.y, 5.0 / 3.0);
    const glm::dvec2 point = footprintCentroid(std::vector<glm::dvec2>{{7, 8}});
    EXPECT_EQ(point, glm::dvec2(7, 8));
    const glm::dvec2 repeated = footprintCentroid(std::vector<glm::dvec2>{{2, 3}, {2, 3}, {2, 3}});
    EXPECT_EQ(repeated, glm::dvec2(2, 3));
    EXPECT_THROW(footprintCentroid(std::vector<glm::dvec2>{}), std::invalid_argument);
}

TEST(FootprintCentroid, ExactFarFromTheOrigin) {
    const glm::dvec2 far{1e7 + 0.25, -1e7 - 0.75};
    const glm::dvec2 c = footprintCentroid(square(far, 0.2));
    EXPECT_NEAR(c.x, far.x, 1e-8);
    EXPECT_NEAR(c.y, far.y, 1e-8);
}

// Cell size 100: centres (0, 0) at (0, 0), (1, 0) at (100 sqrt 3, 0), (0, 1) at (50 sqrt 3, 150).
BuiltScene handBuiltScene() {
    BuiltScene s;
    GrammarBuildings h = houses();
    // A: a 10 m square on the origin, default parameters: 3 * 3 + 2 = 11 m.
    h.buildings.push_back(building(0, square({0, 0}, 5)));
    // B: the bar [70, 110] x [0, 10] with extra points on its left edge. Its area centroid
    // (90, 5) lies past the (0, 0) | (1, 0) edge at x = 50 sqrt 3 = 86.6; its vertex mean
    // (80, 5) does not. 12 storeys on a 5 m base: 5 + 12 * 3 + 2 = 43 m.
    h.buildings.push_back(building(
        1, {{70, 0}, {110, 0}, {110, 10}, {70, 10}, {70, 8}, {70, 6}, {70, 4}, {70, 2}}, 5.0, {12, 3, 2}));
    // C: collinear, so its vertex mean (50, 150) decides: cell (0, 1).
    h.buildings.push_back(building(2, {{40, 140}, {50, 150}, {60, 160}}));
    s.buildingGrammars.push_back(std::move(h));
    GrammarBuildings t = trees();
    t.buildings.push_back(building(3, square({170, 0}, 0.2), 2.0));
    t.buildings.push_back(building(4, square({3, 3}, 0.2)));
    s.treeGrammars.push_back(std::move(t));
    return s;
}

TEST(CellIndex, HandBuiltSceneGivesHandComputedCellsBatchesAndBounds) {
    const BuiltScene s = handBuiltScene();
    const CellIndex index = CellIndex::build(s, 100.0);
    EXPECT_EQ(index.buildingCount(), 3u);
    EXPECT_EQ(index.treeCount(), 2u);
    EXPECT_EQ(index.buildingGrammarCount(), 1u);
    EXPECT_EQ(index.grammarCount(), 2u);
    EXPECT_TRUE(index.isTreeGrammar(1));

    ASSERT_EQ(index.cells().size(), 3u);
    EXPECT_EQ(index.cells()[0].cell, (HexCoord{0, 0}));
    EXPECT_EQ(index.cells()[1].cell, (HexCoord{0, 1}));
    EXPECT_EQ(index.cells()[2].cell, (HexCoord{1, 0}));

    EXPECT_EQ(index.cellOfBuilding(0, 0), (HexCoord{0, 0}));
    EXPECT_EQ(index.cellOfBuilding(0, 1), (HexCoord{1, 0}));
    EXPECT_EQ(index.cellOfBuilding(0, 2), (HexCoord{0, 1}));
    EXPECT_EQ(index.cellOfBuilding(1, 0), (HexCoord{1, 0}));
    EXPECT_EQ(index.cellOfBuilding(1, 1), (HexCoord{0, 0}));
    EXPECT_THROW(index.cellOfBuilding(0, 3), std::out_of_range);
    EXPECT_THROW(index.cellOfBuilding(2, 0), std::out_of_range);

    struct Expected {
        HexCoord cell;
        uint32_t grammar;
        std::vector<uint32_t> buildings;
    };
    const std::vector<Expected> expected{
        {{0, 0}, 0, {0}}, {{0, 0}, 1, {1}}, {{0, 1}, 0, {2}}, {{1, 0}, 0, {1}}, {{1, 0}, 1, {0}}};
    ASSERT_EQ(index.batches().size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(index.batches()[i].cell, expected[i].cell) << i;
        EXPECT_EQ(index.batches()[i].grammar, expected[i].grammar) << i;
        EXPECT_EQ(index.batches()[i].buildings, expected[i].buildings) << i;
    }
    ASSERT_EQ(index.batchesOf({1, 0}).size(), 2u);
    EXPECT_EQ(index.batchesOf({1, 0}).data(), &index.batches()[3]);
    EXPECT_TRUE(index.batchesOf({5, 5}).empty());
    EXPECT_EQ(index.boundsOf({5, 5}), nullptr);

    const double in = 50.0 * kSqrt3; // inradius
    // (0, 0): everything inside the hexagon's box; the tree's 30 m beats the house's 11 m.
    const CellBounds* origin = index.boundsOf({0, 0});
    ASSERT_NE(origin, nullptr);
    EXPECT_NEAR(origin->lo.x, -in, 1e-9);
    EXPECT_NEAR(origin->lo.y, -100.0, 1e-9);
    EXPECT_NEAR(origin->hi.x, in, 1e-9);
    EXPECT_NEAR(origin->hi.y, 100.0, 1e-9);
    EXPECT_EQ(origin->zMin, 0.0);
    EXPECT_EQ(origin->zMax, kDefaultHeight);
    // (1, 0): B reaches out of the hexagon to x = 70 - kFacadeMargin; 43 m tall from 5 m, the
    // tree stands on 2 m.
    const CellBounds* east = index.boundsOf({1, 0});
    ASSERT_NE(east, nullptr);
    EXPECT_NEAR(east->lo.x, 70.0 - kFacadeMargin, 1e-9);
    EXPECT_NEAR(east->lo.y, -100.0, 1e-9);
    EXPECT_NEAR(east->hi.x, 3.0 * in, 1e-9);
    EXPECT_NEAR(east->hi.y, 100.0, 1e-9);
    EXPECT_EQ(east->zMin, 2.0);
    EXPECT_NEAR(east->zMax, 43.0, 1e-9);
    const CellBounds* north = index.boundsOf({0, 1});
    ASSERT_NE(north, nullptr);
    EXPECT_NEAR(north->lo.x, 0.0, 1e-9);
    EXPECT_NEAR(north->lo.y, 50.0, 1e-9);
    EXPECT_NEAR(north->hi.x, 2.0 * in, 1e-9);
    EXPECT_NEAR(north->hi.y, 250.0, 1e-9);
    EXPECT_NEAR(north->zMax, 11.0, 1e-9);
    EXPECT_GT(index.memoryBytes(), sizeof(CellIndex));
}

TEST(CellIndex, TreeCrownsGrowTheBoundsPastTheHexagon) {
    BuiltScene s;
    GrammarBuildings t = trees();
    t.buildings.push_back(building(0, square({80, 0}, 0.2))); // 6.6 m inside the (0, 0) | (1, 0) edge
    s.treeGrammars.push_back(std::move(t));
    const CellIndex index = CellIndex::build(s, 100.0);
    ASSERT_EQ(index.cells().size(), 1u);
    EXPECT_EQ(index.cells()[0].cell, (HexCoord{0, 0}));
    EXPECT_NEAR(index.cells()[0].hi.x, 80.2 + 0.5 * kDefaultHeight, 1e-9);
    EXPECT_EQ(index.buildingCount(), 0u);
    EXPECT_EQ(index.treeCount(), 1u);
}

TEST(CellIndex, EmptySceneHasNoCells) {
    BuiltScene s;
    s.buildingGrammars.push_back(houses());
    const CellIndex index = CellIndex::build(s, 250.0);
    EXPECT_TRUE(index.cells().empty());
    EXPECT_TRUE(index.batches().empty());
    EXPECT_TRUE(index.batchesOf({0, 0}).empty());
}

TEST(CellIndex, BadInputThrowsNamingTheBuilding) {
    BuiltScene s;
    s.buildingGrammars.push_back(houses());
    s.buildingGrammars[0].buildings.push_back(building(41, square({0, 0}, 5)));
    EXPECT_THROW(CellIndex::build(s, 0.0), std::invalid_argument);
    EXPECT_THROW(CellIndex::build(s, std::nan("")), std::invalid_argument);
    s.buildingGrammars[0].buildings.push_back(building(42, {}));
    try {
        CellIndex::build(s, 100.0);
        FAIL() << "an empty footprint must throw";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("'house' building 42: empty footprint"), std::string::npos)
            << e.what();
    }
    s.buildingGrammars[0].buildings.back().footprint = {{0, 0}, {std::numeric_limits<double>::infinity(), 0}};
    EXPECT_THROW(CellIndex::build(s, 100.0), std::invalid_argument);
}

// Squares 2 mm either side of every edge of cells up to 1e7 m out land on their own side.
TEST(CellIndex, AssignmentBesideCellEdgesHoldsFarFromTheOrigin) {
    const double size = 250.0;
    const HexGrid grid(size);
    BuiltScene s;
    s.buildingGrammars.push_back(houses());
    std::vector<HexCoord> expected;
    uint32_t id = 0;
    for (const HexCoord c : {HexCoord{0, 0}, HexCoord{-3, 7}, HexCoord{23094, 0}, HexCoord{-11547, 26667},
                             HexCoord{20000, -20000}}) {
        const std::array<glm::dvec2, 6> corners = grid.corners(c);
        for (size_t i = 0; i < 6; ++i) {
            const HexCoord n{c.q + kHexDirections[i].q, c.r + kHexDirections[i].r};
            const glm::dvec2 mid = 0.5 * (corners[i] + corners[(i + 1) % 6]);
            const glm::dvec2 out = glm::normalize(grid.center(n) - grid.center(c));
            s.buildingGrammars[0].buildings.push_back(building(id++, square(mid - 0.002 * out, 0.2)));
            expected.push_back(c);
            s.buildingGrammars[0].buildings.push_back(building(id++, square(mid + 0.002 * out, 0.2)));
            expected.push_back(n);
        }
    }
    const CellIndex index = CellIndex::build(s, size);
    for (uint32_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(index.cellOfBuilding(0, i), expected[i]) << "building " << i;
    }
}

BuiltScene defaultScene() {
    scene::SceneConfig config;
    std::string error;
    EXPECT_TRUE(scene::loadSceneConfig(HEXLOD_CONFIGS_DIR "/default.json", config, error)) << error;
    BuiltScene s;
    EXPECT_TRUE(scene::buildScene(config, s, error)) << error;
    return s;
}

class DefaultScene : public ::testing::Test {
protected:
    static void SetUpTestSuite() { scene_ = new BuiltScene(defaultScene()); }
    static void TearDownTestSuite() { delete scene_; }
    static const scene::GrammarBuildings& grammarAt(uint32_t g) {
        const size_t nb = scene_->buildingGrammars.size();
        return g < nb ? scene_->buildingGrammars[g] : scene_->treeGrammars[g - nb];
    }
    static BuiltScene* scene_;
};
BuiltScene* DefaultScene::scene_ = nullptr;

TEST_F(DefaultScene, BatchesPartitionEveryGrammarsBuildings) {
    const CellIndex index = CellIndex::build(*scene_, scene_->config.cellSize);
    EXPECT_EQ(index.buildingCount(), scene_->buildingCount());
    EXPECT_EQ(index.treeCount(), scene_->treeCount());
    ASSERT_GT(index.treeCount(), 0u);
    std::vector<std::vector<int>> seen(index.grammarCount());
    for (uint32_t g = 0; g < index.grammarCount(); ++g) seen[g].assign(grammarAt(g).buildings.size(), 0);
    for (size_t i = 0; i < index.batches().size(); ++i) {
        const Batch& batch = index.batches()[i];
        ASSERT_FALSE(batch.buildings.empty());
        EXPECT_TRUE(std::is_sorted(batch.buildings.begin(), batch.buildings.end()));
        if (i > 0) {
            const Batch& previous = index.batches()[i - 1];
            EXPECT_TRUE(previous.cell < batch.cell ||
                        (previous.cell == batch.cell && previous.grammar < batch.grammar));
        }
        for (uint32_t b : batch.buildings) {
            ++seen[batch.grammar][b];
            EXPECT_EQ(index.cellOfBuilding(batch.grammar, b), batch.cell);
        }
    }
    for (uint32_t g = 0; g < index.grammarCount(); ++g) {
        for (size_t b = 0; b < seen[g].size(); ++b)
            ASSERT_EQ(seen[g][b], 1) << "grammar " << g << " building " << b;
    }
    size_t viaCells = 0;
    for (const CellBounds& cell : index.cells()) {
        for (const Batch& batch : index.batchesOf(cell.cell)) {
            EXPECT_EQ(batch.cell, cell.cell);
            viaCells += batch.buildings.size();
        }
    }
    EXPECT_EQ(viaCells, index.buildingCount() + index.treeCount());
}

TEST_F(DefaultScene, EachBuildingsCellHoldsItsCentroidAndBoundsHoldItsFootprint) {
    const CellIndex index = CellIndex::build(*scene_, scene_->config.cellSize);
    const HexGrid& grid = index.grid();
    EXPECT_EQ(grid.origin(), glm::dvec2(0.0));
    for (const CellBounds& cell : index.cells()) {
        for (const glm::dvec2& corner : grid.corners(cell.cell)) {
            EXPECT_GE(corner.x, cell.lo.x - 1e-9);
            EXPECT_GE(corner.y, cell.lo.y - 1e-9);
            EXPECT_LE(corner.x, cell.hi.x + 1e-9);
            EXPECT_LE(corner.y, cell.hi.y + 1e-9);
        }
        EXPECT_LT(cell.zMin, cell.zMax);
    }
    for (uint32_t g = 0; g < index.grammarCount(); ++g) {
        const scene::GrammarBuildings& list = grammarAt(g);
        for (uint32_t i = 0; i < list.buildings.size(); ++i) {
            const BuildingInput& b = list.buildings[i];
            const HexCoord cell = index.cellOfBuilding(g, i);
            ASSERT_TRUE(hexagonContains(grid, cell, footprintCentroid(b.footprint), 1e-9)) << g << " " << i;
            const CellBounds* bounds = index.boundsOf(cell);
            ASSERT_NE(bounds, nullptr);
            for (const glm::dvec2& p : b.footprint) {
                ASSERT_TRUE(p.x >= bounds->lo.x && p.y >= bounds->lo.y && p.x <= bounds->hi.x &&
                            p.y <= bounds->hi.y);
            }
            ASSERT_LE(bounds->zMin, b.baseElevation);
            ASSERT_GT(bounds->zMax, b.baseElevation);
        }
    }
}

TEST_F(DefaultScene, BuildIsDeterministic) {
    expectSameIndex(CellIndex::build(*scene_, scene_->config.cellSize),
                    CellIndex::build(*scene_, scene_->config.cellSize));
    // A scene built afresh from the config indexes the same way.
    const BuiltScene again = defaultScene();
    expectSameIndex(CellIndex::build(*scene_, scene_->config.cellSize),
                    CellIndex::build(again, again.config.cellSize));
}

// The bounds are an estimate made before expansion; they must still hold what expansion makes.
// Checked on the tallest cell of each grammar and the first (an edge cell): every terminal's
// scope, pushed out of its facade by its depth, lies within its cell's bounds.
TEST_F(DefaultScene, ExpandedTerminalsLieWithinTheEstimatedBounds) {
    const CellIndex index = CellIndex::build(*scene_, scene_->config.cellSize);
    std::vector<const Batch*> checked;
    for (uint32_t g = 0; g < index.grammarCount(); ++g) {
        const Batch* first = nullptr;
        const Batch* tallest = nullptr;
        for (const Batch& batch : index.batches()) {
            if (batch.grammar != g) continue;
            if (!first) first = &batch;
            if (!tallest || index.boundsOf(batch.cell)->zMax > index.boundsOf(tallest->cell)->zMax)
                tallest = &batch;
        }
        ASSERT_NE(first, nullptr);
        checked.push_back(first);
        if (tallest != first) checked.push_back(tallest);
    }
    for (const Batch* batch : checked) {
        const scene::GrammarBuildings& list = grammarAt(batch->grammar);
        std::vector<BuildingInput> members;
        for (uint32_t b : batch->buildings) members.push_back(list.buildings[b]);
        grammar::BatchInput input;
        input.grammar = &list.grammar;
        input.buildings = members;
        input.settings.seed = scene_->config.seed;
        const grammar::BatchResult result = grammar::expandBatch(input);
        ASSERT_FALSE(result.failed);
        ASSERT_GT(result.terminals.records.size(), 0u);
        const CellBounds& bounds = *index.boundsOf(batch->cell);
        const double slack = 1e-3; // float positions
        for (const grammar::TerminalRecord& record : result.terminals.records) {
            const grammar::Terminal t = grammar::unpackTerminal(record);
            const glm::vec3 depth = t.normal() * (t.depthRatio * std::min(t.size.x, t.size.y));
            for (const glm::vec3 out : {glm::vec3(0.0f), depth}) {
                for (const glm::vec2 corner :
                     {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(0, 1), glm::vec2(1, 1)}) {
                    const glm::dvec3 p = glm::dvec3(t.position + t.axisX() * (corner.x * t.size.x) +
                                                    t.axisY() * (corner.y * t.size.y) + out);
                    ASSERT_TRUE(p.x >= bounds.lo.x - slack && p.x <= bounds.hi.x + slack &&
                                p.y >= bounds.lo.y - slack && p.y <= bounds.hi.y + slack &&
                                p.z >= bounds.zMin - slack && p.z <= bounds.zMax + slack)
                        << list.name << " cell (" << batch->cell.q << ", " << batch->cell.r << ") building "
                        << t.building << " shape " << list.grammar.shapes[t.shape].name << " at " << p.x
                        << ", " << p.y << ", " << p.z << " outside [" << bounds.lo.x << ", " << bounds.hi.x
                        << "] x [" << bounds.lo.y << ", " << bounds.hi.y << "] x [" << bounds.zMin << ", "
                        << bounds.zMax << "]";
                }
            }
        }
    }
}

// ARCHITECTURE.md §4: the default cell size gives about 100 to 200 buildings per cell. The
// default scene measures 151.5 per cell that holds buildings (66 cells, median 171).
TEST_F(DefaultScene, DefaultCellSizeGivesAbout100To200BuildingsPerCell) {
    const CellIndex index = CellIndex::build(*scene_, scene_->config.cellSize);
    std::set<HexCoord> withBuildings;
    for (const Batch& batch : index.batches()) {
        if (!index.isTreeGrammar(batch.grammar)) withBuildings.insert(batch.cell);
    }
    ASSERT_FALSE(withBuildings.empty());
    const double mean = double(index.buildingCount()) / double(withBuildings.size());
    EXPECT_GT(mean, 120.0);
    EXPECT_LT(mean, 200.0);
    EXPECT_LT(index.memoryBytes(), size_t(1) << 20);
}

} // namespace
} // namespace hexlod::cells
