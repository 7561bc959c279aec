// hexlod export as a library call: a scene config with the journal's edits applied loads
// back to exactly the parameters the service holds.
#include "live_server.h"

#include "hexlod/scene/scene_builder.h"
#include "hexlod/server/scene_export.h"

#include <gtest/gtest.h>

namespace hexlod::test {
namespace {

using Json = nlohmann::json;

std::vector<std::vector<float>> parametersOf(const scene::BuiltScene& scene) {
    std::vector<std::vector<float>> out;
    for (const auto& g : scene.buildingGrammars)
        for (const auto& b : g.buildings) out.push_back(b.parameters);
    for (const auto& g : scene.treeGrammars)
        for (const auto& b : g.buildings) out.push_back(b.parameters);
    return out;
}

scene::SceneConfig loadConfig(const std::string& path) {
    scene::SceneConfig config;
    std::string error;
    EXPECT_TRUE(scene::loadSceneConfig(path, config, error)) << error;
    return config;
}

// Exports the live server's scene and journal to `name` in its folder; returns the path.
std::string exportLive(const LiveServer& live, const std::string& name, server::ExportReport& report) {
    const std::string out = live.folder().file(name);
    std::string error;
    EXPECT_TRUE(
        server::exportEditedScene(loadConfig(live.scenePath()), live.journalPath(), out, report, error))
        << error;
    return out;
}

TEST(SceneExport, TheExportedConfigLoadsBackToTheEditedParameters) {
    SmallScene small;
    small.overrides = Json::array({{{"source", 0}, {"buildings", {5, 6}}, {"params", {{"floors", 3}}}}});
    LiveServer live(small);
    const std::vector<std::string> edits = {
        R"({"selector":{"buildings":[5]},"params":{"floor_h":3.3}})",
        R"({"selector":{"grammar":"business"},"params":{"module_w":2.7}})",
        R"({"selector":{"grammar":2},"params":{"twist":21}})",
        R"({"selector":{"buildings":[1, 2, 3]},"params":{"floor_h":3.25}})",
        R"({"selector":{"buildings":[9]},"params":{"floor_h":4.1}})",
    };
    for (const std::string& e : edits) ASSERT_EQ(live.post("/api/v1/edits", e).status, 200) << e;
    ASSERT_EQ(live.post("/api/v1/edits/undo", "").status, 200); // building 9 back to its value

    server::ExportReport report;
    const std::string out = exportLive(live, "exported.json", report);
    EXPECT_EQ(report.entries, 6u);
    EXPECT_GT(report.editedBuildings, 3u);
    EXPECT_GT(report.editedSpecies, 0u);
    const scene::BuiltScene exported = buildSmallScene(out);
    const auto expected = live.service().withCatalog(
        [](const cells::BatchCatalog& catalog) { return parametersOf(catalog.scene()); });
    EXPECT_EQ(parametersOf(exported), expected);
    // Building 5 kept the config's own override alongside its edit.
    const Json building5 = live.getJson("/api/v1/buildings/5");
    EXPECT_EQ(building5["params"]["floors"], 3.0);
    EXPECT_EQ(building5["params"]["floor_h"], 3.3);
    // The journal was only read.
    EXPECT_EQ(live.getJson("/api/v1/edits")["total"], 6);
}

TEST(SceneExport, TreesOfOneSpeciesEditedApartCannotBeExpressed) {
    const TemporaryFolder folder;
    const std::string path = writeSmallScene(folder.path());
    const scene::SceneConfig config = loadConfig(path);
    const scene::BuiltScene baseline = buildSmallScene(path);
    cells::BatchCatalog catalog(baseline);
    const uint32_t treeGrammar = catalog.index().buildingGrammarCount();
    const uint32_t species = baseline.treeSpecies.at(catalog.grammar(treeGrammar).buildings[0].id);
    size_t sameSpecies = 0;
    for (const grammar::BuildingInput& tree : catalog.grammar(treeGrammar).buildings)
        sameSpecies += baseline.treeSpecies.at(tree.id) == species;
    ASSERT_GE(sameSpecies, 2u);
    ASSERT_TRUE(catalog.setParams(std::vector<cells::BuildingRef>{{treeGrammar, 0}}, {{"twist", 20.0}}).ok);
    scene::SceneConfig out;
    server::ExportReport report;
    std::string error;
    EXPECT_FALSE(server::editedSceneConfig(config, baseline, catalog, out, report, error));
    EXPECT_NE(error.find("per species"), std::string::npos) << error;
}

TEST(SceneExport, WithoutEditsTheConfigComesBackUnchanged) {
    LiveServer live;
    server::ExportReport report;
    const std::string out = exportLive(live, "same.json", report);
    EXPECT_EQ(report.editedBuildings, 0u);
    EXPECT_TRUE(loadConfig(out).overrides.empty());
    EXPECT_EQ(parametersOf(buildSmallScene(out)), parametersOf(buildSmallScene(live.scenePath())));
}

} // namespace
} // namespace hexlod::test
