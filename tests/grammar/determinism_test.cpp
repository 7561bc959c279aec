// Batch expansion must be byte-identical whatever the thread count or input order, and a
// parameter change on one building must change only that building's terminals, so that an
// edited batch can be spliced (batch_splice.h) instead of expanded whole.
#include "test_support.h"

#include "hexlod/grammar/batch_expander.h"
#include "hexlod/grammar/batch_splice.h"
#include "hexlod/grammar/extruded_set_codec.h"
#include "hexlod/scene/demo_footprints.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cstring>
#include <random>

namespace hexlod::grammar {
namespace {

// A grammar with stochastic choices and rand(), so any order dependence would show.
const char* kGrammar = R"(
param floors = 5 in [1, 100];
shape wall(triangles = 2);
shape window(triangles = 150);
shape balcony(triangles = 300);
Lot -> Extrude(floors * 3 + rand(0, 2)) { Facade, NULL };
Facade -> Repeat(y, 3, equal) { Floor };
Floor -> Repeat(x, 2.5, equal) { Tile };
Tile -> Choose(0.6: Win, 0.3: Bal, 0.1: Wall);
Win -> Split(x, ~1, 1.2, ~1) { Wall, Window, Wall };
Bal -> Cond(floor > 0) { Balcony, Win };
Window -> Shape(window);
Balcony -> Shape(balcony, rand(0.2, 0.6));
Wall -> Shape(wall);
)";

std::vector<BuildingInput> demoBuildings(const CompiledGrammar& g, uint32_t count) {
    std::vector<BuildingInput> buildings = scene::makeDemoFootprints({count, 42, 60.0});
    for (BuildingInput& b : buildings) {
        DiagnosticList d;
        b.parameters = resolveParameters(g, scene::demoParameterOverrides(g, 42, b.id), d);
    }
    return buildings;
}

BatchResult expandWithThreads(const CompiledGrammar& g, const std::vector<BuildingInput>& buildings,
                              int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    BatchInput input;
    input.grammar = &g;
    input.buildings = buildings;
    input.settings.seed = 42;
    return expandBatch(input);
}

bool sameBytes(const TerminalSet& a, const TerminalSet& b) {
    return a.records.size() == b.records.size() && a.countPerShape == b.countPerShape &&
           std::memcmp(&a.header, &b.header, sizeof(a.header)) == 0 &&
           std::memcmp(a.records.data(), b.records.data(), a.records.size() * sizeof(TerminalRecord)) == 0;
}

TEST(Determinism, ThreadCountsAndShuffledOrderGiveIdenticalBytes) {
    const CompiledGrammar g = test::compileOrFail(kGrammar);
    const std::vector<BuildingInput> buildings = demoBuildings(g, 400);
    const BatchResult one = expandWithThreads(g, buildings, 1);
    ASSERT_GT(one.terminals.records.size(), 10000u);
    EXPECT_TRUE(sameBytes(one.terminals, expandWithThreads(g, buildings, 2).terminals));
    EXPECT_TRUE(sameBytes(one.terminals, expandWithThreads(g, buildings, 8).terminals));

    std::vector<BuildingInput> shuffled = buildings;
    std::mt19937 rng(7);
    std::shuffle(shuffled.begin(), shuffled.end(), rng);
    const BatchResult reordered = expandWithThreads(g, shuffled, 8);
    EXPECT_TRUE(sameBytes(one.terminals, reordered.terminals));
    EXPECT_EQ(one.extruded.elements.size(), reordered.extruded.elements.size());
    EXPECT_EQ(std::memcmp(one.extruded.footprints.data(), reordered.extruded.footprints.data(),
                          one.extruded.footprints.size() * sizeof(glm::vec2)),
              0);
}

TEST(Determinism, ABuildingExpandsAloneAsInItsBatch) {
    const CompiledGrammar g = test::compileOrFail(kGrammar);
    const std::vector<BuildingInput> buildings = demoBuildings(g, 50);
    const BatchResult all = expandWithThreads(g, buildings, 2);
    const BatchResult alone = expandWithThreads(g, {buildings[17]}, 1);
    size_t matched = 0;
    for (const TerminalRecord& r : all.terminals.records) {
        if (r.building != 17) continue;
        const TerminalRecord& a = alone.terminals.records.at(matched++);
        EXPECT_EQ(std::memcmp(&r, &a, sizeof(r)), 0);
    }
    EXPECT_EQ(matched, alone.terminals.records.size());
}

TEST(Determinism, OneBuildingsParametersChangeOnlyItsTerminals) {
    const CompiledGrammar g = test::compileOrFail(kGrammar);
    std::vector<BuildingInput> buildings = demoBuildings(g, 60);
    const BatchResult before = expandWithThreads(g, buildings, 2);
    DiagnosticList d;
    buildings[23].parameters = resolveParameters(g, {{"floors", 20}}, d);
    const BatchResult after = expandWithThreads(g, buildings, 2);

    auto ofBuilding = [](const TerminalSet& set, uint32_t id, bool wanted) {
        std::vector<TerminalRecord> out;
        for (const TerminalRecord& r : set.records) {
            if ((r.building == id) == wanted) out.push_back(r);
        }
        return out;
    };
    const auto othersBefore = ofBuilding(before.terminals, 23, false),
               othersAfter = ofBuilding(after.terminals, 23, false);
    ASSERT_EQ(othersBefore.size(), othersAfter.size());
    EXPECT_EQ(
        std::memcmp(othersBefore.data(), othersAfter.data(), othersBefore.size() * sizeof(TerminalRecord)),
        0);
    EXPECT_GT(ofBuilding(after.terminals, 23, true).size(), ofBuilding(before.terminals, 23, true).size());
}

// Each case changes some buildings' floors (20 adds storeys, 1 removes every balcony) and
// splices an expansion of them alone into the batch expanded before.
TEST(Determinism, SplicingChangedBuildingsGivesTheWholeExpansionsBytes) {
    const CompiledGrammar g = test::compileOrFail(kGrammar);
    const std::vector<BuildingInput> buildings = demoBuildings(g, 60);
    const BatchResult before = expandWithThreads(g, buildings, 2);
    const int balcony = g.findShape("balcony");
    ASSERT_GE(balcony, 0);
    ASSERT_GT(before.terminals.countPerShape.at(size_t(balcony)), 0u);
    const std::vector<std::pair<std::vector<uint32_t>, float>> cases = {
        {{0}, 20.0f}, {{23}, 20.0f}, {{59}, 20.0f}, {{5, 6, 40}, 1.0f}, {{0, 31, 59}, 20.0f}};
    for (const auto& [ids, floors] : cases) {
        SCOPED_TRACE("buildings " + std::to_string(ids.front()) + ".." + std::to_string(ids.back()));
        std::vector<BuildingInput> after = buildings, changed;
        DiagnosticList d;
        for (const uint32_t id : ids) {
            after[id].parameters = resolveParameters(g, {{"floors", floors}}, d);
            changed.push_back(after[id]);
        }
        const BatchResult whole = expandWithThreads(g, after, 2);
        const BatchResult part = expandWithThreads(g, changed, 2);
        EXPECT_TRUE(sameBytes(whole.terminals, spliceTerminals(before.terminals, part.terminals, ids)));
        const ExtrudedSetHeader header;
        EXPECT_EQ(encodeExtrudedSet(header, whole.extruded),
                  encodeExtrudedSet(header, spliceExtruded(before.extruded, part.extruded, ids)));
        EXPECT_NE(whole.terminals.countPerShape, before.terminals.countPerShape);
    }
}

TEST(Determinism, SplicingABuildingThatExpandsToNothingDropsIt) {
    const CompiledGrammar g = test::compileOrFail(kGrammar);
    std::vector<BuildingInput> buildings = demoBuildings(g, 12);
    const BatchResult before = expandWithThreads(g, buildings, 1);
    buildings[4].footprint = {{0.0, 0.0}, {1.0, 0.0}}; // no area: skipped, with no terminals
    const BatchResult whole = expandWithThreads(g, buildings, 1);
    const BatchResult part = expandWithThreads(g, {buildings[4]}, 1);
    ASSERT_TRUE(part.terminals.records.empty());
    const uint32_t ids[] = {4};
    EXPECT_TRUE(sameBytes(whole.terminals, spliceTerminals(before.terminals, part.terminals, ids)));
    EXPECT_EQ(encodeExtrudedSet({}, whole.extruded),
              encodeExtrudedSet({}, spliceExtruded(before.extruded, part.extruded, ids)));
    EXPECT_LT(whole.extruded.buildings.size(), before.extruded.buildings.size());
}

TEST(Determinism, DuplicateBuildingIdsAreReportedNotMerged) {
    const CompiledGrammar g = test::compileOrFail(kGrammar);
    std::vector<BuildingInput> buildings = demoBuildings(g, 3);
    buildings[2].id = 0;
    const BatchResult r = expandWithThreads(g, buildings, 2);
    EXPECT_EQ(r.buildingsSkipped, 1u);
    ASSERT_FALSE(r.issues.empty());
    EXPECT_EQ(r.issues[0].first.kind, IssueKind::DuplicateBuilding);
}

} // namespace
} // namespace hexlod::grammar
