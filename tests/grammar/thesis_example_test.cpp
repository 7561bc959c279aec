// The thesis §4.6.1 building on a 20 m x 12 m lot: counts and positions computed by hand
// in the comments below, so a change to any rule's arithmetic shows up here.
#include "test_support.h"

#include "hexlod/grammar/batch_expander.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace hexlod::grammar {
namespace {

using test::countByShape;
using test::expandOne;
using test::rectangle;

constexpr float kTolerance = 1e-4f;

CompiledGrammar thesisGrammar() {
    DiagnosticList diagnostics;
    CompiledGrammar g =
        compileGrammarFile(HEXLOD_CONFIGS_DIR "/grammars/thesis-example.grammar", diagnostics);
    EXPECT_FALSE(diagnostics.hasErrors()) << diagnostics.formatAll();
    EXPECT_TRUE(diagnostics.all().empty()) << diagnostics.formatAll();
    return g;
}

const Terminal* findTerminal(const std::vector<Terminal>& terminals, uint16_t shape, glm::vec3 origin) {
    for (const Terminal& t : terminals) {
        if (t.shape == shape && glm::length(t.position - origin) < kTolerance) return &t;
    }
    return nullptr;
}

void expectVec(glm::vec3 actual, glm::vec3 expected, float tolerance = kTolerance) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// Stated parameters: the defaults (floors 4, floor_h 3, tile_w 3, win 1.4 x 1.6, door 1.6 x
// 2.4, ledge 0.3). Facade height 12 m gives 4 floors of 3 m. Tiles per floor: the 20 m edges
// take round(20/3) = 7 tiles of 2.857 m, the 12 m edges 4 tiles of 3 m: 22 per floor.
// Ground floor: tile 0 of each edge is a door tile (4), the other 18 are window tiles.
// Upper floors: 3 x 22 = 66 window tiles and 3 x 4 = 12 ledges.
// Windows: 18 + 66 = 84. Walls: 4 per window tile (2 beside, 2 above/below) = 336, plus 3
// per door tile (2 beside, 1 above the 2.4 m door in a 3 m floor) = 12: 348. Doors: 4.
TEST(ThesisExample, TerminalCountsPerShapeOnA20By12Lot) {
    const CompiledGrammar g = thesisGrammar();
    const test::Expansion e = expandOne(g, rectangle(20, 12));
    const auto counts = countByShape(g, e.terminals);
    EXPECT_EQ(counts.at("window"), 84u);
    EXPECT_EQ(counts.at("door"), 4u);
    EXPECT_EQ(counts.at("ledge"), 12u);
    EXPECT_EQ(counts.at("wall"), 348u);
    EXPECT_EQ(e.terminals.size(), 448u);
    EXPECT_EQ(e.output.atoms, 4u);
    EXPECT_TRUE(e.output.issues.empty());
}

TEST(ThesisExample, SelectedTerminalPositions) {
    const CompiledGrammar g = thesisGrammar();
    const test::Expansion e = expandOne(g, rectangle(20, 12));
    const uint16_t door = uint16_t(g.findShape("door")), window = uint16_t(g.findShape("window")),
                   ledge = uint16_t(g.findShape("ledge"));

    // Door of the south facade (atom 0, x east): tile 0 is 20/7 m wide, the door centred in
    // it at (20/7 - 1.6) / 2 = 0.628571 m; it faces south.
    const Terminal* d = findTerminal(e.terminals, door, {0.628571f, 0.0f, 0.0f});
    ASSERT_NE(d, nullptr);
    EXPECT_NEAR(d->size.x, 1.6f, 1e-3f);
    EXPECT_NEAR(d->size.y, 2.4f, 1e-3f);
    expectVec(d->axisX(), {1, 0, 0}, 1e-3f);
    expectVec(d->normal(), {0, -1, 0}, 1e-3f);

    // East facade (atom 1 runs north along x = 20), floor 2 (6..9 m), tile 1 (3..6 m along
    // the edge): the window column starts 0.8 m into the tile; under the 0.3 m ledge the
    // tile is 2.7 m tall, so the lower wall is (2.7 - 1.6) / 1.6 = 0.6875 m.
    const Terminal* w = findTerminal(e.terminals, window, {20.0f, 3.8f, 6.6875f});
    ASSERT_NE(w, nullptr);
    EXPECT_NEAR(w->size.x, 1.4f, 1e-3f);
    EXPECT_NEAR(w->size.y, 1.6f, 1e-3f);
    expectVec(w->axisX(), {0, 1, 0}, 1e-3f);
    expectVec(w->normal(), {1, 0, 0}, 1e-3f);
    EXPECT_NEAR(w->depthRatio, 0.2f, 1e-3f);

    // North facade (atom 2 runs west from (20, 12)), top floor: the ledge spans the whole
    // 20 m edge at 9 + 2.7 = 11.7 m and faces north.
    const Terminal* l = findTerminal(e.terminals, ledge, {20.0f, 12.0f, 11.7f});
    ASSERT_NE(l, nullptr);
    EXPECT_NEAR(l->size.x, 20.0f, 1e-2f);
    EXPECT_NEAR(l->size.y, 0.3f, 1e-3f);
    expectVec(l->normal(), {0, 1, 0}, 1e-3f);
}

TEST(ThesisExample, ExtrudedSetStopsAfterTheFirstExtrude) {
    const CompiledGrammar g = thesisGrammar();
    EXPECT_TRUE(g.rules[g.findRule("Facade")].extrudedStop);
    EXPECT_TRUE(g.rules[g.findRule("Roof")].extrudedStop);
    EXPECT_FALSE(g.rules[g.findRule("Floor")].extrudedStop);
    const test::Expansion e = expandOne(g, rectangle(20, 12));
    // Four facades of 12 m height and four roof edges (atoms at 12 m).
    ASSERT_EQ(e.output.elements.size(), 8u);
    EXPECT_NEAR(e.output.height, 12.0f, kTolerance);
    size_t faces = 0;
    for (const ExtrudedElement& element : e.output.elements) {
        if (element.size.y > 0) {
            ++faces;
            EXPECT_EQ(g.ruleNames[element.rule], "Facade");
            EXPECT_NEAR(element.size.y, 12.0f, kTolerance);
        } else {
            EXPECT_EQ(g.ruleNames[element.rule], "Roof");
            EXPECT_NEAR(element.origin.z, 12.0f, kTolerance);
        }
    }
    EXPECT_EQ(faces, 4u);
}

TEST(ThesisExample, ParametersChangeTheCountsAsComputed) {
    const CompiledGrammar g = thesisGrammar();
    // 10 floors: 10 x 22 tiles, 4 door tiles, 9 x 4 ledges; windows 220 - 4 = 216.
    const test::Expansion e = expandOne(g, rectangle(20, 12), {{"floors", 10}});
    const auto counts = countByShape(g, e.terminals);
    EXPECT_EQ(counts.at("window"), 216u);
    EXPECT_EQ(counts.at("ledge"), 36u);
    EXPECT_EQ(counts.at("door"), 4u);
}

TEST(ThesisExample, BatchRecordsAreSortedByShapeWithCounts) {
    const CompiledGrammar g = thesisGrammar();
    std::vector<BuildingInput> buildings(3);
    for (uint32_t i = 0; i < 3; ++i) {
        buildings[i].id = i;
        buildings[i].footprint = rectangle(20, 12, {100.0 * i, 0.0});
    }
    BatchInput input;
    input.grammar = &g;
    input.buildings = buildings;
    input.settings.seed = 1;
    input.cell = {3, -2};
    const BatchResult r = expandBatch(input);
    ASSERT_EQ(r.terminals.records.size(), 3 * 448u);
    EXPECT_EQ(r.terminals.countPerShape[g.findShape("window")], 3 * 84u);
    EXPECT_EQ(r.terminals.header.cell.q, 3);
    EXPECT_EQ(r.terminals.header.grammarHash, g.contentHash);
    size_t index = 0;
    for (uint16_t s = 0; s < g.shapes.size(); ++s) {
        EXPECT_EQ(r.terminals.firstOfShape(s), index);
        for (uint32_t k = 0; k < r.terminals.countPerShape[s]; ++k, ++index) {
            EXPECT_EQ(r.terminals.records[index].shapeAndDepth & 0xffffu, s);
        }
    }
    ASSERT_EQ(r.extruded.buildings.size(), 3u);
    EXPECT_EQ(r.extruded.buildings[2].vertexCount, 4u);
    EXPECT_EQ(r.extruded.parameters.size(), 3 * g.params.size());
}

} // namespace
} // namespace hexlod::grammar

namespace hexlod::grammar {
namespace {

// World coordinates stay double until they are made relative to the batch's cell origin, so a
// city 1e7 m from the origin expands to the same cell-local terminals as one at the origin.
TEST(ThesisExample, ExactTenThousandKilometresFromTheOrigin) {
    const CompiledGrammar g = thesisGrammar();
    const glm::dvec2 far(1e7, -1e7);
    ExpansionSettings nearSettings, farSettings;
    nearSettings.seed = farSettings.seed = 1;
    nearSettings.cellOrigin = glm::dvec3(100.0, 50.0, 0.0);
    farSettings.cellOrigin = glm::dvec3(far + glm::dvec2(100.0, 50.0), 0.0);
    const test::Expansion nearby = expandOne(g, rectangle(20, 12, {80.0, 40.0}), {}, 0, nearSettings);
    const test::Expansion distant =
        expandOne(g, rectangle(20, 12, far + glm::dvec2(80.0, 40.0)), {}, 0, farSettings);
    ASSERT_EQ(nearby.terminals.size(), 448u);
    ASSERT_EQ(distant.terminals.size(), nearby.terminals.size());
    float worst = 0.0f;
    for (size_t i = 0; i < nearby.terminals.size(); ++i) {
        worst = std::max(worst, glm::length(nearby.terminals[i].position - distant.terminals[i].position));
        EXPECT_EQ(nearby.terminals[i].shape, distant.terminals[i].shape);
    }
    EXPECT_LT(worst, 1e-3f); // within 1 mm
}

} // namespace
} // namespace hexlod::grammar
