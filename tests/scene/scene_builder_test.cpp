#include "hexlod/scene/scene_builder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace hexlod::scene {
namespace {

const std::string kConfigs = HEXLOD_CONFIGS_DIR;

SceneConfig parse(const std::string& text) {
    SceneConfig config;
    std::string error;
    EXPECT_TRUE(parseSceneConfig(text, "s.json", kConfigs, config, error)) << error;
    return config;
}

std::string buildError(const std::string& text) {
    BuiltScene scene;
    std::string error;
    EXPECT_FALSE(buildScene(parse(text), scene, error));
    return error;
}

bool hasNote(const BuiltScene& scene, const std::string& text) {
    return std::any_of(scene.notes.begin(), scene.notes.end(),
                       [&](const std::string& note) { return note.find(text) != std::string::npos; });
}

const std::string kSmallCity = R"({
  "grammars": { "business": { "file": "grammars/business.grammar" },
                "residential": { "file": "grammars/residential.grammar", "params": { "floor_h": 3.2 } } },
  "buildings": [ { "source": "procedural", "count": 300, "districts": [
      { "grammar": "business", "share": 0.3, "floors": [20, 400] },
      { "grammar": "residential", "share": 0.7, "floors": [2, 5] } ] } ],
  "overrides": [ { "buildings": [7], "params": { "floor_h": 3.4 } } ]
})";

TEST(SceneBuilder, SmallCityWithoutTrees) {
    BuiltScene scene;
    std::string error;
    ASSERT_TRUE(buildScene(parse(kSmallCity), scene, error)) << error;
    EXPECT_EQ(scene.buildingCount(), 300u);
    EXPECT_EQ(scene.treeCount(), 0u);
    EXPECT_TRUE(scene.treeGrammars.empty());
    EXPECT_TRUE(hasNote(scene, "vegetation: off (no trees)"));
    ASSERT_EQ(scene.buildingGrammars.size(), 2u);
    std::set<uint32_t> ids;
    for (const GrammarBuildings& batch : scene.buildingGrammars) {
        EXPECT_FALSE(batch.buildings.empty()) << batch.name;
        const int floors = batch.grammar.findParameter("floors");
        ASSERT_GE(floors, 0);
        const grammar::ParameterInfo& range = batch.grammar.params[floors];
        for (const grammar::BuildingInput& b : batch.buildings) {
            EXPECT_TRUE(ids.insert(b.id).second) << "duplicate id " << b.id;
            ASSERT_EQ(b.parameters.size(), batch.grammar.params.size());
            // District floors are clamped into the grammar's declared range.
            EXPECT_GE(b.parameters[floors], range.minValue);
            EXPECT_LE(b.parameters[floors], range.maxValue);
        }
    }
    const GrammarBuildings& residential = scene.buildingGrammars[1];
    const int floorH = residential.grammar.findParameter("floor_h");
    EXPECT_FLOAT_EQ(residential.buildings.front().parameters[floorH], 3.2f);
    EXPECT_EQ(ids.size(), 300u);
}

TEST(SceneBuilder, TreesCompileTheirSpeciesOnlyWhenPresent) {
    std::string text = kSmallCity;
    text.insert(text.rfind('}'), R"(, "trees": { "count": 120, "species": "species.json" })");
    BuiltScene scene;
    std::string error;
    ASSERT_TRUE(buildScene(parse(text), scene, error)) << error;
    EXPECT_EQ(scene.treeCount(), 120u);
    ASSERT_EQ(scene.treeGrammars.size(), 1u); // seven species share tree.grammar
    EXPECT_TRUE(hasNote(scene, "vegetation: 120 trees of 7 species"));
}

TEST(SceneBuilder, ParameterErrorsNameTheField) {
    std::string badGrammarParam = kSmallCity;
    badGrammarParam.replace(badGrammarParam.find("\"floor_h\": 3.2"), 14, "\"floor_hh\": 3.2");
    EXPECT_NE(buildError(badGrammarParam).find("grammars.residential.params: unknown parameter 'floor_hh'"),
              std::string::npos);

    std::string badOverride = kSmallCity;
    badOverride.replace(badOverride.find("\"floor_h\": 3.4"), 14, "\"floor_h\": 400");
    const std::string error = buildError(badOverride);
    EXPECT_NE(error.find("overrides (buildings[0] building 7)"), std::string::npos) << error;
    EXPECT_NE(error.find("'floor_h' = 400 is outside its range"), std::string::npos) << error;

    std::string missingFile = kSmallCity;
    missingFile.replace(missingFile.find("grammars/business.grammar"), 25, "grammars/nothing.grammar");
    EXPECT_NE(buildError(missingFile).find("grammars.business: "), std::string::npos);
}

TEST(SceneBuilder, ImportedSourcesKeepTheirFeatures) {
    const std::string text = R"({
      "grammars": { "res": { "file": "grammars/residential.grammar" } },
      "buildings": [ { "source": "geojson", "path": ")" HEXLOD_SHARED_DATA_DIR
                             R"(/geojson/utrecht_overture_buildings.geojson", "grammar": "res" },
                     { "source": "osm", "path": ")" HEXLOD_SHARED_DATA_DIR
                             R"(/osm/monaco.osm.pbf", "grammar": "res" } ]
    })";
    BuiltScene scene;
    std::string error;
    ASSERT_TRUE(buildScene(parse(text), scene, error)) << error;
    EXPECT_GE(scene.buildingCount(), 3754u + 23327u);
    // Monaco has no heights: storeys come from the seeded default range, not one value for all.
    const GrammarBuildings& res = scene.buildingGrammars[0];
    const int floors = res.grammar.findParameter("floors");
    std::set<float> storeys;
    for (const grammar::BuildingInput& b : res.buildings) storeys.insert(b.parameters[floors]);
    EXPECT_GE(storeys.size(), 3u);
    ASSERT_EQ(scene.attributions.size(), 1u);
    EXPECT_EQ(scene.attributions[0], "© OpenStreetMap contributors");
    const std::string missing = R"({"grammars": { "res": { "file": "grammars/residential.grammar" } },
      "buildings": [ { "source": "osm", "path": "/no/such.osm.pbf", "grammar": "res" } ]})";
    EXPECT_NE(buildError(missing).find("buildings[0].path: "), std::string::npos);
}

TEST(SceneBuilder, DefaultSceneBuilds) {
    SceneConfig config;
    std::string error;
    ASSERT_TRUE(loadSceneConfig(kConfigs + "/default.json", config, error)) << error;
    BuiltScene scene;
    ASSERT_TRUE(buildScene(config, scene, error)) << error;
    EXPECT_EQ(scene.buildingCount(), 10000u);
    EXPECT_EQ(scene.treeCount(), 20000u);
}

} // namespace
} // namespace hexlod::scene
