#include "hexlod/scene/scene_config.h"

#include <gtest/gtest.h>

#include <string>

namespace hexlod::scene {
namespace {

const std::string kMinimal = R"({
  "grammars": { "res": { "file": "grammars/residential.grammar" } },
  "buildings": [ { "source": "procedural", "count": 50, "districts": [ { "grammar": "res" } ] } ]
})";

std::string parseError(const std::string& text) {
    SceneConfig config;
    std::string error;
    EXPECT_FALSE(parseSceneConfig(text, "s.json", "/base", config, error)) << text;
    return error;
}

// Replaces the first occurrence of `what` in the minimal config.
std::string variant(const std::string& what, const std::string& with) {
    std::string text = kMinimal;
    text.replace(text.find(what), what.size(), with);
    return text;
}

TEST(SceneConfig, MinimalConfigGetsTheDocumentedDefaults) {
    SceneConfig c;
    std::string error;
    ASSERT_TRUE(parseSceneConfig(kMinimal, "configs/s.json", "/base", c, error)) << error;
    EXPECT_EQ(c.name, "s");
    EXPECT_EQ(c.seed, 1u);
    EXPECT_DOUBLE_EQ(c.cellSize, 250.0);
    ASSERT_EQ(c.grammars.size(), 1u);
    EXPECT_EQ(c.grammars[0].path, "/base/grammars/residential.grammar");
    ASSERT_EQ(c.sources.size(), 1u);
    EXPECT_EQ(c.sources[0].city.buildings, 50u);
    EXPECT_EQ(c.sources[0].city.districts[0].grammar, "res");
    EXPECT_EQ(c.trees.count, 0u);
    EXPECT_DOUBLE_EQ(c.lod.maxScreenSpaceError, 2.0);
    EXPECT_EQ(c.cache.memoryBytes, uint64_t(1) << 30);
    EXPECT_TRUE(c.cache.diskPath.empty());
}

TEST(SceneConfig, ShippedConfigsLoad) {
    for (const char* name : {"default.json", "thesis-city.json"}) {
        SceneConfig c;
        std::string error;
        ASSERT_TRUE(loadSceneConfig(std::string(HEXLOD_CONFIGS_DIR) + "/" + name, c, error)) << error;
        EXPECT_EQ(c.grammars.size(), 2u);
        EXPECT_EQ(c.trees.species.size(), 7u) << name;
        EXPECT_NE(c.trees.species[0].grammar.find("grammars/tree.grammar"), std::string::npos);
    }
    SceneConfig thesis;
    std::string error;
    ASSERT_TRUE(loadSceneConfig(std::string(HEXLOD_CONFIGS_DIR) + "/thesis-city.json", thesis, error))
        << error;
    EXPECT_EQ(thesis.sources[0].city.buildings, 116573u);
    EXPECT_EQ(thesis.trees.count, 561280u);
    EXPECT_EQ(thesis.sources[0].city.trees, 561280u);
}

TEST(SceneConfig, EveryFieldIsRead) {
    const std::string text = R"({
      "name": "full", "seed": 99, "cell_size": 120,
      "grammars": { "a": { "file": "a.grammar", "params": { "floor_h": 3.5 } }, "b": { "file": "/abs/b.grammar" } },
      "buildings": [
        { "source": "procedural", "count": 7, "block_size": 90, "street_width": 10, "park_share": 0.1,
          "districts": [ { "grammar": "b", "share": 2, "floors": [10, 40], "lot": [30, 35] },
                         { "grammar": "a" } ] },
        { "source": "geojson", "path": "f.geojson", "grammar": "a" },
        { "source": "osm", "path": "m.osm.pbf", "grammar": "b" } ],
      "overrides": [ { "source": 1, "buildings": [3, 4], "params": { "floors": 9 } } ],
      "trees": { "count": 5, "species": [ { "name": "x", "grammar": "t.grammar", "params": { "leaf_size": 0.3 } } ] },
      "shapes": { "door": { "gltf": "door.glb" } },
      "lod": { "max_screen_space_error": 4, "hysteresis": 0.3, "geometric_error": [20, 5, 1, 0.5, 0],
               "tree_geometric_error": 1.5 },
      "cache": { "memory_mb": 64, "disk_mb": 128, "disk_path": "cache" }
    })";
    SceneConfig c;
    std::string error;
    ASSERT_TRUE(parseSceneConfig(text, "full.json", "/base", c, error)) << error;
    EXPECT_EQ(c.name, "full");
    EXPECT_EQ(c.seed, 99u);
    EXPECT_DOUBLE_EQ(c.cellSize, 120.0);
    EXPECT_DOUBLE_EQ(c.grammars[0].params.at("floor_h"), 3.5);
    EXPECT_EQ(c.grammars[1].path, "/abs/b.grammar");
    const CityOptions& city = c.sources[0].city;
    EXPECT_EQ(city.seed, 99u);
    EXPECT_DOUBLE_EQ(city.blockSize, 90.0);
    EXPECT_DOUBLE_EQ(city.districts[0].maxFloors, 40.0);
    EXPECT_DOUBLE_EQ(city.districts[0].lotDepth, 35.0);
    EXPECT_EQ(city.trees, 5u);
    EXPECT_EQ(city.species, 1u);
    EXPECT_EQ(c.sources[1].kind, BuildingSourceKind::GeoJson);
    EXPECT_EQ(c.sources[2].kind, BuildingSourceKind::Osm);
    EXPECT_EQ(c.sources[2].path, "/base/m.osm.pbf");
    EXPECT_EQ(c.overrides[0].buildings, (std::vector<uint32_t>{3, 4}));
    EXPECT_EQ(c.trees.species[0].grammar, "/base/t.grammar");
    EXPECT_EQ(c.shapes[0].gltf, "/base/door.glb");
    EXPECT_DOUBLE_EQ(c.lod.geometricError[0], 20.0);
    EXPECT_DOUBLE_EQ(c.lod.treeGeometricError, 1.5);
    EXPECT_EQ(c.cache.memoryBytes, uint64_t(64) << 20);
    EXPECT_EQ(c.cache.diskPath, "/base/cache");
}

struct BadConfig {
    const char* name;
    std::string text;
    const char* error;
};

TEST(SceneConfig, BadConfigsNameTheField) {
    const BadConfig cases[] = {
        {"NotJson", "{\"grammars\": ", "s.json:1:14: not valid JSON"},
        {"NumberOverflow", variant("\"grammars\"", "\"cell_size\": 1e999, \"grammars\""),
         "s.json:2:16: a number is out of range (1e999 does not fit a double)"},
        {"NotAnObject", "[1]", "s.json: top level: expected an object"},
        {"MissingGrammars", R"({"buildings": []})", "s.json: grammars: is required"},
        {"Typo", variant("\"grammars\"", "\"cel_size\": 3, \"grammars\""), "s.json: cel_size: unknown field"},
        {"CellSizeNaNLike", variant("\"grammars\"", "\"cell_size\": -5, \"grammars\""),
         "s.json: cell_size: must be a finite number in [1, 100000], got -5"},
        {"CellSizeString", variant("\"grammars\"", "\"cell_size\": \"big\", \"grammars\""),
         "s.json: cell_size: expected a number"},
        {"SeedNegative", variant("\"grammars\"", "\"seed\": -1, \"grammars\""),
         "s.json: seed: expected a whole number"},
        {"GrammarWithoutFile", variant("{ \"file\": \"grammars/residential.grammar\" }", "{}"),
         "s.json: grammars.res.file: is required"},
        {"UnknownDistrictGrammar", variant("\"grammar\": \"res\"", "\"grammar\": \"offices\""),
         "s.json: buildings[0].districts[0].grammar: names no grammar in \"grammars\": 'offices'"},
        {"FloorsReversed", variant("\"grammar\": \"res\"", "\"grammar\": \"res\", \"floors\": [9, 3]"),
         "s.json: buildings[0].districts[0].floors: min is greater than max"},
        {"LotTooSmall", variant("\"grammar\": \"res\"", "\"grammar\": \"res\", \"lot\": [1, 3]"),
         "s.json: buildings[0].districts[0].lot: lots must be at least 4 m wide"},
        {"CountFractional", variant("\"count\": 50", "\"count\": 2.5"),
         "s.json: buildings[0].count: expected a whole number"},
        {"CountHuge", variant("\"count\": 50", "\"count\": 1e12"),
         "s.json: buildings[0].count: expected a whole number"},
        {"NoDistricts", variant("[ { \"grammar\": \"res\" } ]", "[]"),
         "s.json: buildings[0].districts: expected a non-empty array"},
        {"UnknownSource", variant("\"procedural\"", "\"shapefile\""),
         "s.json: buildings[0].source: expected \"procedural\", \"geojson\" or \"osm\""},
        {"ParkShare", variant("\"count\": 50", "\"count\": 50, \"park_share\": 1.5"),
         "s.json: buildings[0].park_share: must be a finite number in [0, 0.9]"},
        {"OverrideSource",
         variant("\"buildings\": [", "\"overrides\": [{\"source\": 3, \"buildings\": [1], "
                                     "\"params\": {}}], \"buildings\": ["),
         "s.json: overrides[0].source: names no building source"},
        {"TreesWithoutSpecies", variant("\"buildings\": [", "\"trees\": {\"count\": 4}, \"buildings\": ["),
         "s.json: trees.species: trees need species"},
        {"MissingSpeciesFile",
         variant("\"buildings\": [", "\"trees\": {\"count\": 4, \"species\": \"none.json\"}, "
                                     "\"buildings\": ["),
         "s.json: trees.species: cannot open species file '/base/none.json'"},
        {"LodOrder",
         variant("\"buildings\": [", "\"lod\": {\"geometric_error\": [1, 2, 0, 0, 0]}, \"buildings\": ["),
         "s.json: lod.geometric_error: errors must not grow from LOD0 to LOD4"},
        {"LodCount", variant("\"buildings\": [", "\"lod\": {\"geometric_error\": [1]}, \"buildings\": ["),
         "s.json: lod.geometric_error: expected 5 numbers, LOD0 to LOD4"},
        {"TreeErrorNegative",
         variant("\"buildings\": [", "\"lod\": {\"tree_geometric_error\": -0.5}, \"buildings\": ["),
         "s.json: lod.tree_geometric_error: must be a finite number in [0, 1e+06], got -0.5"},
        {"TreeErrorHuge",
         variant("\"buildings\": [", "\"lod\": {\"tree_geometric_error\": 1e300}, \"buildings\": ["),
         "s.json: lod.tree_geometric_error: must be a finite number in [0, 1e+06], got 1e+300"},
        {"TreeErrorNotNumber",
         variant("\"buildings\": [", "\"lod\": {\"tree_geometric_error\": \"far\"}, \"buildings\": ["),
         "s.json: lod.tree_geometric_error: "},
        {"CacheZero", variant("\"buildings\": [", "\"cache\": {\"memory_mb\": 0}, \"buildings\": ["),
         "s.json: cache.memory_mb: must be at least 1"},
        {"ParamNotNumber",
         variant("\"file\": \"grammars/residential.grammar\"",
                 "\"file\": \"grammars/residential.grammar\", \"params\": {\"floors\": \"x\"}"),
         "s.json: grammars.res.params.floors: expected a number"},
    };
    for (const BadConfig& c : cases) {
        const std::string error = parseError(c.text);
        EXPECT_EQ(error.rfind(c.error, 0), 0u) << c.name << ": " << error;
    }
}

} // namespace
} // namespace hexlod::scene
