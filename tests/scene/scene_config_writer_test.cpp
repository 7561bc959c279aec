// Writing a scene config back: the shipped configs survive write-then-load with every field,
// paths rewritten relative to the new file's folder.
#include "hexlod/scene/scene_config.h"
#include "hexlod/scene/scene_config_writer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

namespace hexlod::scene {
namespace {

namespace fs = std::filesystem;

std::string absolute(const std::string& path) {
    return fs::absolute(path).lexically_normal().string();
}

void expectSameConfig(const SceneConfig& a, const SceneConfig& b) {
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.seed, b.seed);
    EXPECT_EQ(a.cellSize, b.cellSize);
    ASSERT_EQ(a.grammars.size(), b.grammars.size());
    for (size_t i = 0; i < a.grammars.size(); ++i) {
        EXPECT_EQ(a.grammars[i].name, b.grammars[i].name);
        EXPECT_EQ(absolute(a.grammars[i].path), absolute(b.grammars[i].path));
        EXPECT_EQ(a.grammars[i].params, b.grammars[i].params);
    }
    ASSERT_EQ(a.sources.size(), b.sources.size());
    for (size_t i = 0; i < a.sources.size(); ++i) {
        const BuildingSource &x = a.sources[i], &y = b.sources[i];
        EXPECT_EQ(x.kind, y.kind);
        EXPECT_EQ(x.city.buildings, y.city.buildings);
        EXPECT_EQ(x.city.blockSize, y.city.blockSize);
        EXPECT_EQ(x.city.streetWidth, y.city.streetWidth);
        EXPECT_EQ(x.city.parkShare, y.city.parkShare);
        EXPECT_EQ(x.city.trees, y.city.trees);
        ASSERT_EQ(x.city.districts.size(), y.city.districts.size());
        for (size_t d = 0; d < x.city.districts.size(); ++d) {
            EXPECT_EQ(x.city.districts[d].grammar, y.city.districts[d].grammar);
            EXPECT_EQ(x.city.districts[d].share, y.city.districts[d].share);
            EXPECT_EQ(x.city.districts[d].minFloors, y.city.districts[d].minFloors);
            EXPECT_EQ(x.city.districts[d].lotDepth, y.city.districts[d].lotDepth);
        }
    }
    ASSERT_EQ(a.overrides.size(), b.overrides.size());
    for (size_t i = 0; i < a.overrides.size(); ++i) {
        EXPECT_EQ(a.overrides[i].buildings, b.overrides[i].buildings);
        EXPECT_EQ(a.overrides[i].params, b.overrides[i].params);
    }
    EXPECT_EQ(a.trees.count, b.trees.count);
    ASSERT_EQ(a.trees.species.size(), b.trees.species.size());
    for (size_t i = 0; i < a.trees.species.size(); ++i) {
        EXPECT_EQ(a.trees.species[i].name, b.trees.species[i].name);
        EXPECT_EQ(absolute(a.trees.species[i].grammar), absolute(b.trees.species[i].grammar));
        EXPECT_EQ(a.trees.species[i].params, b.trees.species[i].params);
    }
    EXPECT_EQ(a.lod.maxScreenSpaceError, b.lod.maxScreenSpaceError);
    EXPECT_EQ(a.lod.hysteresis, b.lod.hysteresis);
    EXPECT_EQ(a.lod.geometricError, b.lod.geometricError);
    EXPECT_EQ(a.lod.treeGeometricError, b.lod.treeGeometricError);
    EXPECT_EQ(a.cache.memoryBytes, b.cache.memoryBytes);
    EXPECT_EQ(a.cache.diskBytes, b.cache.diskBytes);
}

TEST(SceneConfigWriter, ShippedConfigsSurviveWriteThenLoad) {
    std::string folder = (fs::temp_directory_path() / "hexlod-writer-XXXXXX").string();
    ASSERT_TRUE(mkdtemp(folder.data()));
    for (const char* name : {"default.json", "thesis-city.json"}) {
        SceneConfig original;
        std::string error;
        ASSERT_TRUE(loadSceneConfig(std::string(HEXLOD_CONFIGS_DIR) + "/" + name, original, error)) << error;
        original.overrides.push_back({0, {3, 4}, {{"floors", 5.0}, {"floor_h", 3.25}}});
        original.lod.treeGeometricError = 1.5; // not the default, so a writer that drops it fails
        const std::string path = folder + "/nested/out-" + name;
        fs::create_directories(fs::path(path).parent_path());
        ASSERT_TRUE(writeSceneConfig(original, path, error)) << error;
        SceneConfig back;
        ASSERT_TRUE(loadSceneConfig(path, back, error)) << error;
        expectSameConfig(original, back);
        const nlohmann::json written = sceneConfigToJson(original, fs::path(path).parent_path().string());
        EXPECT_FALSE(fs::path(written["grammars"]["residential"]["file"].get<std::string>()).is_absolute());
    }
    SceneConfig any;
    std::string error;
    EXPECT_FALSE(writeSceneConfig(any, folder + "/missing/folder/out.json", error));
    EXPECT_NE(error.find("cannot write"), std::string::npos);
    fs::remove_all(folder);
}

} // namespace
} // namespace hexlod::scene
