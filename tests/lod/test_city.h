// Small cities for the LOD tests: a procedural city of a few blocks from the shipped grammars,
// optionally far from the world origin, with its catalog, cache and meshes.
#pragma once

#include "hexlod/cache/terminal_set_cache.h"
#include "hexlod/cells/batch_catalog.h"
#include "hexlod/render/terminal_mesh_library.h"
#include "hexlod/scene/scene_builder.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace hexlod::lod::testing {

struct TestCity {
    std::unique_ptr<cells::BatchCatalog> catalog;
    std::unique_ptr<cache::TerminalSetCache> cache;
    std::unique_ptr<render::TerminalMeshLibrary> meshes;
};

inline std::string cityConfig(uint32_t buildings, uint32_t trees, const std::string& origin = "[0, 0, 0]") {
    return R"({"name": "test", "seed": 3, "cell_size": 120, "origin": )" + origin +
           R"(, "grammars": {"business": {"file": "grammars/business.grammar"},
                "residential": {"file": "grammars/residential.grammar"}},
  "buildings": [{"source": "procedural", "count": )" +
           std::to_string(buildings) +
           R"(, "block_size": 90, "street_width": 12, "park_share": 0.1,
    "districts": [{"grammar": "business", "share": 0.3, "floors": [10, 30], "lot": [30, 30]},
                  {"grammar": "residential", "share": 0.7, "floors": [2, 6], "lot": [16, 20]}]}],
  "trees": {"count": )" +
           std::to_string(trees) + R"(, "species": "species.json"}})";
}

inline TestCity makeCity(uint32_t buildings, uint32_t trees, const std::string& origin = "[0, 0, 0]") {
    TestCity city;
    scene::SceneConfig config;
    std::string error;
    EXPECT_TRUE(scene::parseSceneConfig(cityConfig(buildings, trees, origin), "test.json", HEXLOD_CONFIGS_DIR,
                                        config, error))
        << error;
    scene::BuiltScene built;
    EXPECT_TRUE(scene::buildScene(config, built, error)) << error;
    city.catalog = std::make_unique<cells::BatchCatalog>(std::move(built));
    city.cache = std::make_unique<cache::TerminalSetCache>(cache::CacheOptions{});
    std::vector<const grammar::CompiledGrammar*> grammars;
    for (uint32_t g = 0; g < city.catalog->index().grammarCount(); ++g)
        grammars.push_back(&city.catalog->grammar(g).grammar);
    city.meshes = std::make_unique<render::TerminalMeshLibrary>(grammars);
    return city;
}

} // namespace hexlod::lod::testing
