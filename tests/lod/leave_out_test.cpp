// What the renderer leaves out (ARCHITECTURE.md §8): a scene without trees allocates no tree
// buffers and bakes no tree impostor, one grammar compiles one LOD1 interpreter, tree grammars
// compile none, and a frame generates only the batches of cells in view.
#include "../render/gl_fixture.h"
#include "test_city.h"

#include "hexlod/lod/city_renderer.h"

namespace hexlod::lod {
namespace {

class LeaveOutTest : public render::GlTest {
protected:
    struct Opened {
        SceneImpostors impostors;
        SceneImpostorReport report;
        std::unique_ptr<CityRenderer> renderer;
    };

    static std::unique_ptr<Opened> open(testing::TestCity& city) {
        auto out = std::make_unique<Opened>();
        SceneImpostorOptions options;
        options.facadeLayout = {impostor::ViewSphere::Hemisphere, 2, 16, 2};
        options.treeLayout = {impostor::ViewSphere::FullSphere, 2, 16, 2};
        std::string error;
        EXPECT_TRUE(bakeSceneImpostors(city.catalog->scene(), *city.meshes, options, out->impostors,
                                       out->report, error))
            << error;
        CityRendererOptions renderOptions;
        renderOptions.width = 64;
        renderOptions.height = 48;
        renderOptions.arenaRecords = 1 << 18;
        out->renderer = std::make_unique<CityRenderer>(*city.catalog, *city.cache, *city.meshes,
                                                       &out->impostors, renderOptions);
        EXPECT_TRUE(out->renderer->init(error)) << error;
        return out;
    }

    static scene::CameraPose streetView(const cells::BatchCatalog& catalog) {
        const cells::CellBounds& cell = catalog.index().cells().front();
        scene::CameraPose pose;
        pose.position = glm::dvec3(cell.lo.x - 20.0, cell.lo.y - 20.0, 30.0);
        pose.forward = glm::normalize(glm::dvec3(1.0, 1.0, -0.3));
        pose.up = glm::dvec3(0, 0, 1);
        return pose;
    }
};

TEST_F(LeaveOutTest, WithoutTreesNoTreeBufferAndNoTreeImpostor) {
    testing::TestCity city = testing::makeCity(12, 0);
    const auto opened = open(city);
    EXPECT_EQ(opened->report.treeSpecies, 0u);
    EXPECT_TRUE(opened->impostors.species.empty());
    EXPECT_EQ(opened->renderer->treeBytes(), 0u);
    const FrameStats stats = opened->renderer->render(streetView(*city.catalog), 0.0, 0.5, 5000.0);
    EXPECT_EQ(stats.treeBillboards, 0u);

    // The same city with trees does both, so the zero above is the scene's doing.
    testing::TestCity wooded = testing::makeCity(12, 20);
    const auto withTrees = open(wooded);
    EXPECT_GT(withTrees->report.treeSpecies, 0u);
    EXPECT_GT(withTrees->renderer->treeBytes(), 0u);
}

TEST_F(LeaveOutTest, OneLod1InterpreterPerBuildingGrammar) {
    // Business, residential and a tree grammar; both building grammars have buildings.
    testing::TestCity two = testing::makeCity(60, 10);
    for (const scene::GrammarBuildings& g : two.catalog->scene().buildingGrammars)
        ASSERT_FALSE(g.buildings.empty());
    EXPECT_EQ(open(two)->renderer->summary(), "LOD1 shaders: 2 grammars");
    // A grammar without buildings compiles none (12 buildings near the centre are all one district's).
    testing::TestCity few = testing::makeCity(12, 0);
    size_t used = 0;
    for (const scene::GrammarBuildings& g : few.catalog->scene().buildingGrammars)
        used += !g.buildings.empty();
    ASSERT_EQ(used, 1u);
    EXPECT_EQ(open(few)->renderer->summary(), "LOD1 shaders: 1 grammar");

    scene::SceneConfig config;
    std::string error;
    ASSERT_TRUE(scene::loadSceneConfig(std::string(HEXLOD_TESTS_DIR) + "/lod/scenes/three_shapes.json",
                                       config, error))
        << error;
    scene::BuiltScene built;
    ASSERT_TRUE(scene::buildScene(config, built, error)) << error;
    testing::TestCity one;
    one.catalog = std::make_unique<cells::BatchCatalog>(std::move(built));
    one.cache = std::make_unique<cache::TerminalSetCache>(cache::CacheOptions{});
    const grammar::CompiledGrammar* grammars[] = {&one.catalog->grammar(0).grammar};
    one.meshes = std::make_unique<render::TerminalMeshLibrary>(grammars);
    const auto opened = open(one);
    EXPECT_EQ(opened->renderer->summary(), "LOD1 shaders: 1 grammar");
    EXPECT_EQ(opened->report.shapes.size(), 3u); // three emitted shapes, three bakes
}

TEST_F(LeaveOutTest, AFrameGeneratesOnlyTheBatchesOfCellsInView) {
    testing::TestCity city = testing::makeCity(60, 0);
    const auto opened = open(city);
    scene::CameraPose pose = streetView(*city.catalog);
    pose.forward = glm::normalize(glm::dvec3(-1.0, -1.0, -0.3)); // away from the city
    opened->renderer->render(pose, 0.0, 0.5, 5000.0);
    EXPECT_EQ(city.cache->stats().lookups, 0u) << "nothing in view, nothing generated";
    pose = streetView(*city.catalog);
    const FrameStats stats = opened->renderer->render(pose, 1.0, 0.5, 5000.0);
    EXPECT_GT(stats.cacheLookups, 0u);
    EXPECT_LT(city.cache->stats().lookups, city.catalog->batchCount()) << "only the cells in view";
}

} // namespace
} // namespace hexlod::lod
