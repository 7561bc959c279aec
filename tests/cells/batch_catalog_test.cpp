// Tests of the batch catalog: keys per batch, generation relative to the cell centre, and
// edits at library level (exactly the affected keys change, invalid edits change nothing,
// undo finds the cached entry again), on a small procedural city.
#include "hexlod/cells/batch_catalog.h"

#include "hexlod/scene/scene_builder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

namespace hexlod::cells {

// A city small enough for sanitizer builds: 400 buildings on 120 m cells, with trees. District
// storeys stay below the values the edits set, so an edit always changes every batch it selects.
scene::BuiltScene smallCity() {
    const std::string text = R"({
      "name": "small", "seed": 7, "cell_size": 120,
      "grammars": { "business": { "file": "grammars/business.grammar" },
                    "residential": { "file": "grammars/residential.grammar" } },
      "buildings": [ { "source": "procedural", "count": 400, "block_size": 90, "street_width": 12,
        "districts": [ { "grammar": "business", "share": 0.2, "floors": [4, 9], "lot": [30, 30] },
                       { "grammar": "residential", "share": 0.8, "floors": [2, 5], "lot": [16, 20] } ] } ],
      "trees": { "count": 120, "species": "species.json" }
    })";
    scene::SceneConfig config;
    std::string error;
    EXPECT_TRUE(scene::parseSceneConfig(text, "small.json", HEXLOD_CONFIGS_DIR, config, error)) << error;
    scene::BuiltScene built;
    EXPECT_TRUE(scene::buildScene(config, built, error)) << error;
    return built;
}

namespace {

std::vector<cache::BatchKey> keysOf(const BatchCatalog& catalog) {
    std::vector<cache::BatchKey> keys;
    for (uint32_t b = 0; b < catalog.batchCount(); ++b) keys.push_back(catalog.key(b));
    return keys;
}

std::set<uint32_t> changedBatches(const std::vector<cache::BatchKey>& before, const BatchCatalog& catalog) {
    std::set<uint32_t> changed;
    for (uint32_t b = 0; b < catalog.batchCount(); ++b)
        if (!(catalog.key(b) == before[b])) changed.insert(b);
    return changed;
}

std::set<uint32_t> batchesIn(const EditResult& result) {
    std::set<uint32_t> batches;
    for (const KeyChange& change : result.changed) batches.insert(change.batch);
    return batches;
}

class BatchCatalogTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() { scene_ = new scene::BuiltScene(smallCity()); }
    static void TearDownTestSuite() { delete scene_; }
    BatchCatalog catalog_{*scene_};
    static scene::BuiltScene* scene_;
};
scene::BuiltScene* BatchCatalogTest::scene_ = nullptr;

TEST_F(BatchCatalogTest, KeysAreStableAcrossCatalogsOfTheSameScene) {
    ASSERT_GE(catalog_.index().buildingGrammarCount(), 2u);
    ASSERT_GT(catalog_.batchCount(), 20u);
    const BatchCatalog again(*scene_);
    EXPECT_EQ(keysOf(again), keysOf(catalog_));
    std::set<uint64_t> digests;
    for (const cache::BatchKey& key : keysOf(catalog_)) digests.insert(key.digest());
    EXPECT_EQ(digests.size(), catalog_.batchCount());
    const Batch& first = catalog_.batch(0);
    EXPECT_EQ(catalog_.key(0).cell.q, first.cell.q);
    EXPECT_EQ(catalog_.key(0).grammar, first.grammar);
    EXPECT_EQ(catalog_.key(0).grammarHash, catalog_.grammar(first.grammar).grammar.contentHash);
}

TEST_F(BatchCatalogTest, AnEditOfOneBuildingChangesExactlyTheKeyOfItsBatch) {
    const auto before = keysOf(catalog_);
    const uint32_t grammar = 1, building = 17;
    const HexCoord cell = catalog_.index().cellOfBuilding(grammar, building);
    const auto cellBatches = catalog_.index().batchesOf(cell);
    uint32_t expected = catalog_.firstBatchOf(cell);
    while (catalog_.batch(expected).grammar != grammar) ++expected;
    ASSERT_LT(expected, catalog_.firstBatchOf(cell) + cellBatches.size());

    const EditResult result =
        catalog_.setParams(std::vector<BuildingRef>{{grammar, building}}, {{"floors", 12.0}});
    ASSERT_TRUE(result.ok) << result.error;
    ASSERT_EQ(result.changed.size(), 1u);
    EXPECT_EQ(result.changed[0].batch, expected);
    EXPECT_EQ(result.changed[0].before, before[expected]);
    EXPECT_EQ(result.changed[0].after, catalog_.key(expected));
    EXPECT_EQ(changedBatches(before, catalog_), std::set<uint32_t>{expected});
    const auto& params = catalog_.grammar(grammar).buildings[building].parameters;
    EXPECT_EQ(params[catalog_.grammar(grammar).grammar.findParameter("floors")], 12.0f);

    // The same building by its scene-wide id is the same edit target.
    const uint32_t id = catalog_.grammar(grammar).buildings[building].id;
    const auto middle = keysOf(catalog_);
    const EditResult byId = catalog_.setParams(BuildingIds{{id}}, {{"floors", 11.0}});
    ASSERT_TRUE(byId.ok) << byId.error;
    EXPECT_EQ(changedBatches(middle, catalog_), std::set<uint32_t>{expected});
}

TEST_F(BatchCatalogTest, ACellSelectorChangesExactlyThatCellsBatches) {
    // The cell with the most batches, so that several grammars are involved.
    HexCoord cell = catalog_.index().cells()[0].cell;
    for (const CellBounds& c : catalog_.index().cells())
        if (catalog_.index().batchesOf(c.cell).size() > catalog_.index().batchesOf(cell).size())
            cell = c.cell;
    ASSERT_GE(catalog_.index().batchesOf(cell).size(), 2u);
    std::set<uint32_t> expected;
    const uint32_t first = catalog_.firstBatchOf(cell);
    for (uint32_t b = first; b < first + catalog_.index().batchesOf(cell).size(); ++b)
        if (!catalog_.index().isTreeGrammar(catalog_.batch(b).grammar))
            expected.insert(b); // trees lack floors
    ASSERT_FALSE(expected.empty());

    const auto before = keysOf(catalog_);
    const EditResult result = catalog_.setParams(cell, {{"floors", 12.0}});
    ASSERT_TRUE(result.ok) << result.error;
    EXPECT_EQ(batchesIn(result), expected);
    EXPECT_EQ(changedBatches(before, catalog_), expected);
}

TEST_F(BatchCatalogTest, AGrammarSelectorChangesExactlyThatGrammarsBatches) {
    const uint32_t residential = 1;
    ASSERT_EQ(catalog_.grammar(residential).name, "residential");
    std::set<uint32_t> expected;
    for (uint32_t b = 0; b < catalog_.batchCount(); ++b)
        if (catalog_.batch(b).grammar == residential) expected.insert(b);

    const auto before = keysOf(catalog_);
    const EditResult byName = catalog_.setParams(GrammarName{"residential"}, {{"floors", 12.0}});
    ASSERT_TRUE(byName.ok) << byName.error;
    EXPECT_EQ(batchesIn(byName), expected);
    EXPECT_EQ(changedBatches(before, catalog_), expected);

    const auto middle = keysOf(catalog_);
    const EditResult byIndex = catalog_.setParams(GrammarIndex{residential}, {{"window_w", 2.0}});
    ASSERT_TRUE(byIndex.ok) << byIndex.error;
    EXPECT_EQ(changedBatches(middle, catalog_), expected);
}

TEST_F(BatchCatalogTest, AnInvalidEditChangesNothingAndNamesTheParameter) {
    const auto before = keysOf(catalog_);
    const auto parameters = catalog_.grammar(0).buildings[3].parameters;
    const std::vector<BuildingRef> one{{0, 3}};
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    const struct {
        Selector selector;
        scene::ParameterMap values;
        std::string named;
    } cases[] = {
        {one, {{"no_such_param", 1.0}}, "no_such_param"},
        {one, {{"floors", nan}}, "floors"},
        {one, {{"floors", inf}}, "floors"},
        {one, {{"floors", 1000.0}}, "floors"},
        {one, {{"floors", 0.0}}, "floors"},
        // All or nothing: the valid value is not applied either.
        {one, {{"floors", 20.0}, {"module_w", 99.0}}, "module_w"},
        {GrammarIndex{1}, {{"floors", 13.0}}, "floors"}, // residential allows 12 at most
        {BuildingIds{{1u << 30}}, {{"floors", 5.0}}, "1073741824"},
        {std::vector<BuildingRef>{{0, 1u << 30}}, {{"floors", 5.0}}, "1073741824"},
        {HexCoord{1000, 1000}, {{"floors", 5.0}}, "(1000, 1000)"},
        {GrammarName{"castle"}, {{"floors", 5.0}}, "castle"},
        {GrammarIndex{99}, {{"floors", 5.0}}, "99"},
        {one, {}, "no parameter"},
    };
    for (const auto& c : cases) {
        const EditResult result = catalog_.setParams(c.selector, c.values);
        EXPECT_FALSE(result.ok) << c.named;
        EXPECT_NE(result.error.find(c.named), std::string::npos) << result.error;
        EXPECT_TRUE(result.changed.empty());
    }
    EXPECT_EQ(keysOf(catalog_), before);
    EXPECT_EQ(catalog_.grammar(0).buildings[3].parameters, parameters);
    EXPECT_EQ(catalog_.historySize(), 0u);
}

TEST_F(BatchCatalogTest, UndoRestoresTheOldKeysAndTheCachedEntry) {
    cache::TerminalSetCache cache(cache::CacheOptions{});
    const uint32_t building = 5;
    const HexCoord cell = catalog_.index().cellOfBuilding(0, building);
    uint32_t batch = catalog_.firstBatchOf(cell);
    while (catalog_.batch(batch).grammar != 0) ++batch;

    const auto original = keysOf(catalog_);
    const auto first = catalog_.fetch(batch, cache);
    ASSERT_TRUE(first);
    EXPECT_EQ(first->header.key, original[batch].digest());
    EXPECT_EQ(cache.stats().misses, 1u);

    ASSERT_TRUE(catalog_.setParams(std::vector<BuildingRef>{{0, building}}, {{"floors", 30.0}}).ok);
    ASSERT_TRUE(catalog_.setParams(GrammarIndex{0}, {{"floor_h", 4.5}}).ok);
    EXPECT_EQ(catalog_.historySize(), 2u);
    const auto edited = catalog_.fetch(batch, cache);
    EXPECT_EQ(cache.stats().misses, 2u);
    EXPECT_GT(edited->records.size(), first->records.size()); // taller building, taller storeys

    const EditResult second = catalog_.undo();
    ASSERT_TRUE(second.ok) << second.error;
    const EditResult firstUndo = catalog_.undo();
    ASSERT_TRUE(firstUndo.ok) << firstUndo.error;
    ASSERT_EQ(firstUndo.changed.size(), 1u);
    EXPECT_EQ(firstUndo.changed[0].batch, batch);
    EXPECT_EQ(firstUndo.changed[0].after, original[batch]);
    EXPECT_EQ(keysOf(catalog_), original);
    for (size_t i = 0; i < scene_->buildingGrammars[0].buildings.size(); ++i)
        ASSERT_EQ(catalog_.grammar(0).buildings[i].parameters,
                  scene_->buildingGrammars[0].buildings[i].parameters);

    const uint64_t hits = cache.stats().hits;
    const auto again = catalog_.fetch(batch, cache);
    EXPECT_EQ(cache.stats().hits, hits + 1);
    EXPECT_EQ(cache.stats().misses, 2u);
    EXPECT_EQ(again.get(), first.get());

    const EditResult none = catalog_.undo();
    EXPECT_FALSE(none.ok);
    EXPECT_FALSE(none.error.empty());
}

TEST_F(BatchCatalogTest, GeneratedTerminalsAreRelativeToTheCellCentre) {
    size_t checked = 0;
    for (uint32_t b = 0; b < catalog_.batchCount() && checked < 6; b += 7, ++checked) {
        const Batch& batch = catalog_.batch(b);
        const grammar::TerminalSet set = catalog_.generate(b);
        ASSERT_FALSE(set.records.empty()) << "batch " << b;
        EXPECT_EQ(set.header.cell.q, batch.cell.q);
        EXPECT_EQ(set.header.cell.r, batch.cell.r);
        EXPECT_EQ(set.header.grammar, batch.grammar);
        EXPECT_EQ(set.header.key, catalog_.key(b).digest());
        const glm::dvec3 origin = catalog_.cellOrigin(batch.cell);
        EXPECT_EQ(glm::dvec2(origin), catalog_.index().grid().center(batch.cell));
        EXPECT_EQ(set.header.cellOrigin[0], origin.x);
        EXPECT_EQ(set.header.cellOrigin[1], origin.y);
        const CellBounds* bounds = catalog_.index().boundsOf(batch.cell);
        const double margin = 1.0;
        for (const grammar::TerminalRecord& record : set.records) {
            const glm::dvec3 p(record.position[0], record.position[1], record.position[2]);
            ASSERT_GE(p.x, bounds->lo.x - origin.x - margin);
            ASSERT_LE(p.x, bounds->hi.x - origin.x + margin);
            ASSERT_GE(p.y, bounds->lo.y - origin.y - margin);
            ASSERT_LE(p.y, bounds->hi.y - origin.y + margin);
            ASSERT_GE(p.z, bounds->zMin - margin);
            ASSERT_LE(p.z, bounds->zMax + margin);
        }
        // The hexagon's circumradius bounds the centre's distance to any building's centroid,
        // so positions are small numbers, not world coordinates.
        EXPECT_LT(std::abs(set.records.front().position[0]), 3.0 * catalog_.scene().config.cellSize);
    }
    EXPECT_EQ(checked, 6u);
}

TEST_F(BatchCatalogTest, ExtrudedOnlyExpansionGivesTheSameBaseVolumes) {
    for (uint32_t b = 0; b < catalog_.batchCount(); b += 5) {
        const grammar::ExtrudedSet whole = catalog_.expand(b).extruded;
        const grammar::ExtrudedSet alone = catalog_.expandExtruded(b);
        ASSERT_EQ(alone.buildings.size(), whole.buildings.size()) << "batch " << b;
        ASSERT_EQ(alone.elements.size(), whole.elements.size()) << "batch " << b;
        for (size_t i = 0; i < whole.buildings.size(); ++i) {
            EXPECT_EQ(alone.buildings[i].building, whole.buildings[i].building);
            EXPECT_EQ(alone.buildings[i].height, whole.buildings[i].height);
            EXPECT_EQ(alone.buildings[i].vertexCount, whole.buildings[i].vertexCount);
        }
        for (size_t i = 0; i < whole.elements.size(); ++i) {
            EXPECT_EQ(alone.elements[i].origin, whole.elements[i].origin);
            EXPECT_EQ(alone.elements[i].size, whole.elements[i].size);
            EXPECT_EQ(alone.elements[i].rule, whole.elements[i].rule);
        }
        EXPECT_EQ(alone.footprints, whole.footprints);
        EXPECT_EQ(alone.parameters, whole.parameters);
    }
}

} // namespace
} // namespace hexlod::cells
