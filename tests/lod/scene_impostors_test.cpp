// What a scene bakes: the shapes its grammars emit and nothing else, a species impostor per
// tree species only when it has trees (from the coarse parts its samples cannot tell apart),
// loads from the store instead of baking again, and a corrupt file baked again.
#include "../render/gl_fixture.h"
#include "test_city.h"

#include "hexlod/lod/scene_impostors.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

namespace hexlod::lod {
namespace {

class SceneImpostorsTest : public render::GlTest {
protected:
    static testing::TestCity loadScene(const std::string& path) {
        testing::TestCity city;
        scene::SceneConfig config;
        std::string error;
        EXPECT_TRUE(scene::loadSceneConfig(path, config, error)) << error;
        scene::BuiltScene built;
        EXPECT_TRUE(scene::buildScene(config, built, error)) << error;
        city.catalog = std::make_unique<cells::BatchCatalog>(std::move(built));
        std::vector<const grammar::CompiledGrammar*> grammars;
        for (uint32_t g = 0; g < city.catalog->index().grammarCount(); ++g)
            grammars.push_back(&city.catalog->grammar(g).grammar);
        city.meshes = std::make_unique<render::TerminalMeshLibrary>(grammars);
        return city;
    }
    static SceneImpostorOptions smallOptions(const std::string& store = "") {
        SceneImpostorOptions options;
        options.facadeLayout = {impostor::ViewSphere::Hemisphere, 4, 32, 2};
        options.treeLayout = {impostor::ViewSphere::FullSphere, 4, 32, 2};
        options.storeDirectory = store;
        return options;
    }
};

TEST_F(SceneImpostorsTest, AGrammarThatEmitsThreeShapesBakesThreeAndNoTrees) {
    testing::TestCity city = loadScene(std::string(HEXLOD_TESTS_DIR) + "/lod/scenes/three_shapes.json");
    SceneImpostors impostors;
    SceneImpostorReport report;
    std::string error;
    ASSERT_TRUE(
        bakeSceneImpostors(city.catalog->scene(), *city.meshes, smallOptions(), impostors, report, error))
        << error;
    ASSERT_EQ(impostors.facades.size(), 3u);
    std::set<std::string> names;
    for (const impostor::ImpostorAtlas& atlas : impostors.facades) names.insert(atlas.shape);
    EXPECT_EQ(names, (std::set<std::string>{"wall", "window", "door"}));
    EXPECT_EQ(report.declaredShapes, 6u);
    EXPECT_EQ(report.skippedUnused, 3u);
    EXPECT_TRUE(impostors.species.empty());
    EXPECT_EQ(report.treeSpecies, 0u);
    EXPECT_EQ(report.summary(),
              "impostors: 3 of 6 declared shapes baked (used by this scene): 3 new, 0 loaded from the store");
    // Shapes without an impostor map to -1, the others to their atlas.
    const grammar::CompiledGrammar& g = city.catalog->grammar(0).grammar;
    EXPECT_EQ(impostors.facadeLayer[0][size_t(g.findShape("balcony"))], -1);
    EXPECT_GE(impostors.facadeLayer[0][size_t(g.findShape("window"))], 0);
}

TEST_F(SceneImpostorsTest, EverySpeciesWithTreesGetsOneFullSphereImpostor) {
    testing::TestCity city = testing::makeCity(20, 60);
    SceneImpostors impostors;
    SceneImpostorReport report;
    std::string error;
    ASSERT_TRUE(
        bakeSceneImpostors(city.catalog->scene(), *city.meshes, smallOptions(), impostors, report, error))
        << error;
    std::set<std::vector<float>> species;
    for (const auto& trees : city.catalog->scene().treeGrammars)
        for (const grammar::BuildingInput& tree : trees.buildings) species.insert(tree.parameters);
    EXPECT_EQ(impostors.species.size(), species.size());
    for (const impostor::ImpostorAtlas& atlas : impostors.species) {
        EXPECT_EQ(atlas.layout.sphere, impostor::ViewSphere::FullSphere);
        EXPECT_EQ(atlas.shape.rfind("tree:", 0), 0u);
        EXPECT_GT(atlas.boundsMax.z, 1.0f); // a tree stands up from its base
    }
}

TEST_F(SceneImpostorsTest, ASpeciesIsBakedFromTheCoarsePartsItsSamplesCannotTellApart) {
    testing::TestCity city = testing::makeCity(20, 60);
    const scene::BuiltScene& built = city.catalog->scene();
    ASSERT_FALSE(built.treeGrammars.empty());
    const scene::GrammarBuildings& trees = built.treeGrammars[0];
    const uint32_t grammarIndex = uint32_t(built.buildingGrammars.size()); // tree grammars come after
    const auto geometry = [&](float spacing) {
        return treeGeometry(trees.grammar, trees.buildings.at(0).parameters, built.config.seed, *city.meshes,
                            grammarIndex, spacing);
    };
    const impostor::BakeGeometry full = geometry(0.0f);
    // A spacing no coarse mesh fits under changes nothing; a metre takes every coarse part.
    const impostor::BakeGeometry fine = geometry(1e-6f);
    EXPECT_EQ(fine.hash, full.hash);
    EXPECT_EQ(fine.indices, full.indices);
    const impostor::BakeGeometry coarsest = geometry(1.0f);
    EXPECT_NE(coarsest.hash, full.hash) << "the bake's key must tell the two apart";
    EXPECT_LT(2 * coarsest.indices.size(), full.indices.size());

    // At the spacing bakeTreeSpecies bakes at, the views are those of the full parts.
    const impostor::ViewLayout layout = smallOptions().treeLayout;
    impostor::ImpostorAtlas frame;
    impostor::measureGeometry(full, frame);
    const float spacing =
        2.0f * frame.radius / float(layout.innerResolution() * impostor::ImpostorBaker::kSupersampling);
    const impostor::BakeGeometry used = geometry(spacing);
    EXPECT_LT(used.indices.size(), full.indices.size());
    impostor::ImpostorBaker baker;
    std::string error;
    ASSERT_TRUE(baker.init(error)) << error;
    impostor::ImpostorAtlas fromFull, fromUsed;
    ASSERT_TRUE(baker.bake(full, layout, fromFull, error)) << error;
    ASSERT_TRUE(baker.bake(used, layout, fromUsed, error)) << error;
    EXPECT_NEAR(fromUsed.radius, fromFull.radius, 0.02f * fromFull.radius);
    // Colour times coverage, so that a texel the coarse parts leave empty counts as black.
    double squared = 0.0, coverage = 0.0;
    const std::vector<float>& a = fromFull.albedo.pixels;
    const std::vector<float>& b = fromUsed.albedo.pixels;
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); i += 4) {
        for (size_t c = 0; c < 3; ++c) {
            const double d = double(a[i + c]) * a[i + 3] - double(b[i + c]) * b[i + 3];
            squared += d * d;
        }
        coverage += std::abs(double(a[i + 3]) - double(b[i + 3]));
    }
    const double texels = double(a.size() / 4);
    const double psnr = 10.0 * std::log10(1.0 / (squared / (3.0 * texels)));
    std::printf("%zu of %zu indices at %.3f m spacing: %.1f dB, mean coverage difference %.4f\n",
                used.indices.size(), full.indices.size(), spacing, psnr, coverage / texels);
    EXPECT_GT(psnr, 40.0);
    EXPECT_LT(coverage / texels, 0.01);
}

TEST_F(SceneImpostorsTest, TheStoreSkipsRebakesAndRecoversACorruptFile) {
    testing::TestCity city = loadScene(std::string(HEXLOD_TESTS_DIR) + "/lod/scenes/three_shapes.json");
    const auto store =
        std::filesystem::temp_directory_path() / ("hexlod-scene-store-" + std::to_string(::getpid()));
    std::filesystem::remove_all(store);
    std::string error;
    auto bake = [&](SceneImpostorReport& report) {
        SceneImpostors impostors;
        EXPECT_TRUE(bakeSceneImpostors(city.catalog->scene(), *city.meshes, smallOptions(store.string()),
                                       impostors, report, error))
            << error;
        return impostors;
    };
    SceneImpostorReport first, second, third;
    SceneImpostors baked = bake(first);
    for (const BakedShapeReport& shape : first.shapes)
        EXPECT_EQ(shape.outcome, BakeOutcome::Baked) << shape.name;
    EXPECT_GT(first.fileBytes, 0u);
    SceneImpostors loaded = bake(second);
    for (const BakedShapeReport& shape : second.shapes)
        EXPECT_EQ(shape.outcome, BakeOutcome::Loaded) << shape.name;
    for (size_t i = 0; i < baked.facades.size(); ++i)
        EXPECT_EQ(loaded.facades[i].albedo.pixels, baked.facades[i].albedo.pixels);
    // Truncate one file: that shape is baked again and says why; the others still load.
    std::filesystem::path victim;
    for (const auto& entry : std::filesystem::directory_iterator(store))
        if (entry.path().filename().string().rfind("window-", 0) == 0) victim = entry.path();
    ASSERT_FALSE(victim.empty());
    std::filesystem::resize_file(victim, std::filesystem::file_size(victim) / 3);
    bake(third);
    for (const BakedShapeReport& shape : third.shapes) {
        if (shape.name == "window") {
            EXPECT_EQ(shape.outcome, BakeOutcome::Rebaked);
            EXPECT_FALSE(shape.note.empty());
        } else {
            EXPECT_EQ(shape.outcome, BakeOutcome::Loaded) << shape.name;
        }
    }
    std::filesystem::remove_all(store);
}

} // namespace
} // namespace hexlod::lod
