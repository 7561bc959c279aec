// The whole frame on llvmpipe: every mode renders a small city, the LOD system costs less than
// everything at LOD4 and stays close to it, LOD0's walls show bays where LOD4 shows windows,
// multisampling antialiases, tree billboards cover what their trees cover with and without it and
// shade only their species' box, billboards beyond LOD2's distance are flat and show the same
// trees, trees a pixel across are points that cover as much, the profile's tree error places the
// cut, far tree parts draw coarser meshes, double-sided leaves draw each triangle once and look
// as before, hidden billboards and LOD3 impostors are dropped without
// changing a pixel, a city 1e7 m out renders as at the origin, odd cameras render without error,
// and golden images hold each mode's look.
#include "../render/gl_fixture.h"
#include "test_city.h"

#include "hexlod/lod/city_renderer.h"
#include "hexlod/render/gl_api.h"
#include "hexlod/render/image_io.h"
#include "hexlod/render/image_metrics.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace hexlod::lod {
namespace {

constexpr uint32_t kWidth = 160, kHeight = 96;

struct Rendered {
    render::Image image;
    FrameStats stats;
};

class CityRendererTest : public render::GlTest {
protected:
    // Bakes the city's impostors small (4 x 4 views of 32 texels) to keep the test quick.
    SceneImpostors bake(const testing::TestCity& city) {
        SceneImpostorOptions options;
        options.facadeLayout = {impostor::ViewSphere::Hemisphere, 4, 32, 2};
        options.treeLayout = {impostor::ViewSphere::FullSphere, 4, 32, 2};
        SceneImpostors impostors;
        SceneImpostorReport report;
        std::string error;
        EXPECT_TRUE(
            bakeSceneImpostors(city.catalog->scene(), *city.meshes, options, impostors, report, error))
            << error;
        return impostors;
    }

    Rendered render(testing::TestCity& city, const SceneImpostors& impostors, RenderMode mode,
                    const scene::CameraPose& pose, uint32_t frames = 1, uint32_t samples = 1,
                    bool dropHidden = true, const scene::LodProfile& lod = {},
                    double treePointsUnderSse = 2.0, bool fitTreeBillboards = true,
                    double buildingPointsUnderSse = 2.0, bool shadeFarWallsAtMean = true) {
        CityRendererOptions options;
        options.buildingPointsUnderSse = buildingPointsUnderSse;
        options.shadeFarWallsAtMean = shadeFarWallsAtMean;
        options.fitTreeBillboards = fitTreeBillboards;
        options.lod = lod;
        options.treePointsUnderSse = treePointsUnderSse;
        options.dropHidden = dropHidden;
        options.width = kWidth;
        options.height = kHeight;
        options.mode = mode;
        options.samples = samples;
        options.arenaRecords = 1 << 20;
        CityRenderer renderer(*city.catalog, *city.cache, *city.meshes, &impostors, options);
        std::string error;
        EXPECT_TRUE(renderer.init(error)) << error;
        Rendered out;
        for (uint32_t f = 0; f < frames; ++f) out.stats = renderer.render(pose, double(f), 0.5, 5000.0);
        out.image = renderer.readColor();
        return out;
    }

    // The tree tests' park: trees only, 120 of the shipped species, with their impostors.
    struct Park {
        testing::TestCity city;
        SceneImpostors impostors;
    };
    Park park() {
        Park p{testing::makeCity(0, 120), {}};
        p.impostors = bake(p.city);
        return p;
    }
    // The view across the park from 12 m up, where most of its trees are billboards.
    static scene::CameraPose acrossThePark() { return lookAt({-60, -70, 12}, {0, 0, 5}); }

    static scene::CameraPose lookAt(glm::dvec3 eye, glm::dvec3 target, double fovDegrees = 60.0) {
        scene::CameraPose pose;
        pose.position = eye;
        pose.forward = glm::normalize(target - eye);
        // The renderer rebuilds an up vector that is not usable (here: looking straight down).
        pose.up = glm::dvec3(0, 0, 1);
        pose.fovY = fovDegrees * 3.14159265358979 / 180.0;
        return pose;
    }

    // Share of pixels that are not the sky colour: something was drawn.
    static double coverage(const render::Image& image) {
        size_t drawn = 0;
        for (uint32_t y = 0; y < image.height; ++y)
            for (uint32_t x = 0; x < image.width; ++x)
                if (std::abs(image.at(x, y)[2] - 0.84f) > 0.02f ||
                    std::abs(image.at(x, y)[0] - 0.62f) > 0.02f)
                    ++drawn;
        return double(drawn) / double(image.width * image.height);
    }

    // Goldens are llvmpipe's images (CI's renderer); another GPU rasterises differently.
    void expectGolden(const render::Image& image, const std::string& name, double minPsnr = 35.0) {
        if (!context().info().software) return;
        const std::string path = std::string(HEXLOD_TESTS_DIR) + "/lod/golden/" + name + ".exr";
        std::string error;
        if (std::getenv("HEXLOD_UPDATE_GOLDEN")) {
            std::filesystem::create_directories(std::filesystem::path(path).parent_path());
            ASSERT_TRUE(render::writeExr(path, image, error)) << error;
            return;
        }
        render::Image golden;
        ASSERT_TRUE(render::readExr(path, golden, error)) << error << " (HEXLOD_UPDATE_GOLDEN=1 writes it)";
        const double psnr = render::compareImages(image, golden).psnr;
        EXPECT_GE(psnr, minPsnr) << name << " differs from its golden image";
    }
};

TEST_F(CityRendererTest, EveryModeRendersAndTheLodSystemStaysCloseToLod4ForLess) {
    testing::TestCity city = testing::makeCity(50, 40);
    const SceneImpostors impostors = bake(city);
    const scene::CameraPose pose = lookAt({-220, -260, 60}, {0, 0, 10});
    Rendered reference = render(city, impostors, RenderMode::AllLod4, pose);
    EXPECT_GT(coverage(reference.image), 0.3);
    EXPECT_GT(reference.stats.terminalsPerLod[4], 0u);
    for (RenderMode mode : {RenderMode::Lod, RenderMode::AllLod3, RenderMode::AllLod2, RenderMode::AllLod1,
                            RenderMode::AllLod0}) {
        Rendered r = render(city, impostors, mode, pose);
        EXPECT_GT(coverage(r.image), 0.3) << renderModeName(mode);
        const double psnr = render::compareImages(r.image, reference.image).psnr;
        EXPECT_GT(psnr, 16.0) << renderModeName(mode);
        expectGolden(r.image, std::string("city_") + renderModeName(mode));
        if (mode == RenderMode::AllLod3) {
            EXPECT_GT(r.stats.terminalsPerLod[3], 0u);
        }
        if (mode == RenderMode::AllLod2) {
            EXPECT_GT(r.stats.terminalsPerLod[2], 0u);
        }
        if (mode == RenderMode::AllLod1) {
            EXPECT_GT(r.stats.cellsPerLod[1], 0u);
        }
        if (mode == RenderMode::AllLod0 || mode == RenderMode::AllLod1) {
            // Extruded cells draw their trees as billboards, which the goldens then hold.
            EXPECT_GT(r.stats.treeBillboards, 0u) << renderModeName(mode);
            EXPECT_EQ(r.stats.terminalsPerLod[4] + r.stats.terminalsPerLod[3] + r.stats.terminalsPerLod[2],
                      0u);
        }
    }
    expectGolden(reference.image, "city_lod4");
}

TEST_F(CityRendererTest, MultisamplingAntialiasesTheFrame) {
    // Buildings only, all geometry: one sample per pixel and four differ at the silhouettes
    // alone, so a target left at one sample would render the same image twice.
    testing::TestCity city = testing::makeCity(30, 0);
    const SceneImpostors impostors = bake(city);
    const scene::CameraPose pose = lookAt({-150, -180, 30}, {0, 0, 10});
    Rendered one = render(city, impostors, RenderMode::AllLod4, pose, 1, 1);
    Rendered four = render(city, impostors, RenderMode::AllLod4, pose, 1, 4);
    const double psnr = render::compareImages(four.image, one.image).psnr;
    std::printf("4 samples against 1: %.1f dB\n", psnr);
    EXPECT_LT(psnr, 50.0) << "four samples per pixel rendered what one does";
    EXPECT_GT(psnr, 20.0);
}

TEST_F(CityRendererTest, Lod0WallsShowStoreysAndBaysWhereTheirTerminalsWouldBe) {
    // At street level, buildings only: LOD0's wall texture draws window bays where LOD4 draws
    // windows, so that the walls break up into about as many edges; walls without it (the
    // shells under terminal sets, the ground's program) would show a face's one colour.
    testing::TestCity city = testing::makeCity(30, 0);
    const SceneImpostors impostors = bake(city);
    const scene::CameraPose pose = lookAt({-60, -70, 3}, {0, 0, 12});
    // Pixels whose colour differs from their left neighbour's by more than a few levels.
    const auto edges = [](const render::Image& image) {
        size_t count = 0;
        for (uint32_t y = 0; y < image.height; ++y)
            for (uint32_t x = 1; x < image.width; ++x)
                for (int c = 0; c < 3; ++c)
                    if (std::abs(image.at(x, y)[c] - image.at(x - 1, y)[c]) > 0.03f) {
                        ++count;
                        break;
                    }
        return count;
    };
    const size_t lod4 = edges(render(city, impostors, RenderMode::AllLod4, pose).image);
    const size_t lod0 = edges(render(city, impostors, RenderMode::AllLod0, pose).image);
    std::printf("edges: %zu at LOD4, %zu at LOD0\n", lod4, lod0);
    EXPECT_GT(lod4, 500u);
    EXPECT_GT(lod0, lod4 / 2);
}

TEST_F(CityRendererTest, MultisampledTreeBillboardsCoverWhatTheirTreesCover) {
    // Trees only, nearly all of them billboards. With multisampling their alpha becomes
    // coverage; drawn into a target left at one sample, every faint texel would cover its
    // whole pixel and rows of far crowns would stack into solid ones (4 dB worse than one
    // sample per pixel; 4 dB better when the target is multisampled).
    auto [city, impostors] = park();
    const scene::CameraPose pose = acrossThePark();
    double psnr[2] = {0.0, 0.0};
    for (uint32_t pass = 0; pass < 2; ++pass) {
        const uint32_t samples = pass == 0 ? 1 : 4;
        Rendered trees = render(city, impostors, RenderMode::AllLod4, pose, 1, samples);
        Rendered billboards = render(city, impostors, RenderMode::Lod, pose, 1, samples);
        ASSERT_GT(billboards.stats.treeBillboards, 0u);
        psnr[pass] = render::compareImages(billboards.image, trees.image).psnr;
        std::printf("%u samples: billboards against tree geometry %.2f dB\n", samples, psnr[pass]);
    }
    EXPECT_GT(psnr[1], psnr[0] - 2.0) << "multisampled billboards cover more than their trees";
}

TEST_F(CityRendererTest, TreesAPixelOrTwoAcrossArePointsThatCoverWhatTheirBillboardsCover) {
    // Trees only, from 300 m: each about three pixels across, under the point size (twice the
    // default 2 px error bound).
    auto [city, impostors] = park();
    const scene::CameraPose pose = lookAt({-200, -220, 40}, {0, 0, 0});
    Rendered trees = render(city, impostors, RenderMode::AllLod4, pose, 1, 4);
    Rendered points = render(city, impostors, RenderMode::Lod, pose, 1, 4);
    Rendered billboards = render(city, impostors, RenderMode::Lod, pose, 1, 4, true, {}, 0.0);
    EXPECT_GT(points.stats.treePoints, 0u);
    EXPECT_EQ(billboards.stats.treePoints, 0u);
    EXPECT_GT(billboards.stats.treeBillboards, 0u);
    EXPECT_NE(points.image.pixels, billboards.image.pixels);
    const double pointError = render::compareImages(points.image, trees.image).psnr,
                 billboardError = render::compareImages(billboards.image, trees.image).psnr;
    std::printf("against tree geometry: points %.2f dB, billboards %.2f dB\n", pointError, billboardError);
    EXPECT_GT(pointError, billboardError - 1.0);
}

// Fragment shader invocations between construction and destruction
// (ARB_pipeline_statistics_query); 0 where the GL does not count them.
class FragmentInvocations {
public:
    FragmentInvocations() {
        GLint extensions = 0;
        gl::glGetIntegerv(GL_NUM_EXTENSIONS, &extensions);
        for (GLint i = 0; i < extensions; ++i)
            if (std::string(reinterpret_cast<const char*>(gl::glGetStringi(GL_EXTENSIONS, GLuint(i)))) ==
                "GL_ARB_pipeline_statistics_query")
                gl::glGenQueries(1, &query_); // Mesa's glCreateQueries refuses this target
        if (query_) gl::glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, query_);
    }
    ~FragmentInvocations() {
        if (query_) gl::glDeleteQueries(1, &query_);
    }
    uint64_t count() {
        if (!query_) return 0;
        gl::glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
        uint64_t invocations = 0;
        gl::glGetQueryObjectui64v(query_, GL_QUERY_RESULT, &invocations);
        return invocations;
    }

private:
    GLuint query_ = 0;
};

TEST_F(CityRendererTest, TreeBillboardsCoverTheirSpeciesBoxAloneAndDrawTheSameImage) {
    // Trees only, every one a billboard (a tree error of 5 cm). A billboard over its species'
    // box rather than its sphere's square leaves out pixels where the impostor shows nothing:
    // the same image (the box holds every surface the views saw) for far fewer fragments. The
    // billboards' fragments are the frame's less those of the same frame with points instead.
    auto [city, impostors] = park();
    const scene::CameraPose pose = acrossThePark();
    scene::LodProfile lod;
    lod.treeGeometricError = 0.05;
    const Rendered trees = render(city, impostors, RenderMode::AllLod4, pose, 1, 4);
    uint64_t fragments[3] = {0, 0, 0}; // points, squares, boxes
    Rendered frames[3];
    for (int i = 0; i < 3; ++i) {
        FragmentInvocations invocations;
        frames[i] =
            render(city, impostors, RenderMode::Lod, pose, 1, 4, true, lod, i == 0 ? 1e9 : 2.0, i == 2);
        fragments[i] = invocations.count();
    }
    EXPECT_EQ(frames[0].stats.treeBillboards, 0u);
    ASSERT_GT(frames[1].stats.treeBillboards, 0u);
    EXPECT_EQ(frames[2].stats.treeBillboards, frames[1].stats.treeBillboards);
    const double between = render::compareImages(frames[2].image, frames[1].image).psnr,
                 square = render::compareImages(frames[1].image, trees.image).psnr,
                 box = render::compareImages(frames[2].image, trees.image).psnr;
    std::printf("billboard fragments: %lld over the squares, %lld over the boxes; boxes against squares "
                "%.1f dB; against tree geometry %.2f dB (squares) and %.2f dB (boxes)\n",
                static_cast<long long>(fragments[1] - fragments[0]),
                static_cast<long long>(fragments[2] - fragments[0]), between, square, box);
    EXPECT_GT(between, 50.0);
    EXPECT_GT(box, square - 0.05);
    if (fragments[1] == 0 && !context().info().software) return; // this GL does not count them
    EXPECT_GT(fragments[1], fragments[0]) << "llvmpipe counts fragment shader invocations";
    EXPECT_LT(fragments[2] - fragments[0], (fragments[1] - fragments[0]) * 2 / 3);
}

TEST_F(CityRendererTest, TheProfilesTreeErrorPlacesTheCutBetweenTreesAndBillboards) {
    // Trees only, so every LOD4 terminal is a tree's. A billboard is accepted where the tree
    // error stays under the budget: a small error makes every tree a billboard, a huge one
    // none, one in between keeps the near trees geometry; 0 turns billboards off.
    auto [city, impostors] = park();
    const scene::CameraPose pose = acrossThePark();
    const double errors[4] = {0.0, 0.05, 2.0, 1e3};
    uint64_t treeTerminals[4] = {0, 0, 0, 0};
    for (size_t i = 0; i < 4; ++i) {
        scene::LodProfile lod;
        lod.treeGeometricError = errors[i];
        treeTerminals[i] =
            render(city, impostors, RenderMode::Lod, pose, 1, 1, true, lod).stats.terminalsPerLod[4];
        std::printf("tree error %g m: %llu tree terminals drawn\n", errors[i],
                    static_cast<unsigned long long>(treeTerminals[i]));
    }
    EXPECT_GT(treeTerminals[0], 0u);
    EXPECT_EQ(treeTerminals[3], treeTerminals[0]);
    EXPECT_EQ(treeTerminals[1], 0u);
    EXPECT_GT(treeTerminals[2], 0u);
    EXPECT_LT(treeTerminals[2], treeTerminals[0]);
}

TEST_F(CityRendererTest, FarTreePartsDrawCoarserMeshesThatLookTheSameForFewerTriangles) {
    // Trees only and no billboards (tree error 0), so the LOD system and the reference draw
    // the same tree terminals at LOD4; the LOD system draws the far ones' coarser meshes.
    auto [city, impostors] = park();
    const scene::CameraPose pose = acrossThePark();
    scene::LodProfile lod;
    lod.treeGeometricError = 0.0;
    const Rendered full = render(city, impostors, RenderMode::AllLod4, pose, 1, 4);
    const Rendered coarse = render(city, impostors, RenderMode::Lod, pose, 1, 4, true, lod);
    EXPECT_EQ(coarse.stats.terminalsPerLod[4], full.stats.terminalsPerLod[4]);
    EXPECT_EQ(coarse.stats.treeBillboards, 0u);
    EXPECT_EQ(full.stats.coarseTerminals, 0u);
    EXPECT_GT(coarse.stats.coarseTerminals, 0u);
    // At 160 x 96 pixels every part here is small enough (CullRulesTest checks the distance).
    EXPECT_LE(coarse.stats.coarseTerminals, coarse.stats.terminalsPerLod[4]);
    const double psnr = render::compareImages(coarse.image, full.image).psnr;
    std::printf("coarse tree parts: %llu of %llu triangles, %.2f dB against full meshes\n",
                static_cast<unsigned long long>(coarse.stats.triangles),
                static_cast<unsigned long long>(full.stats.triangles), psnr);
    EXPECT_LT(coarse.stats.triangles, full.stats.triangles * 3 / 4);
    EXPECT_GT(psnr, 35.0);
}

TEST_F(CityRendererTest, DoubleSidedTreePartsDrawEachTriangleOnceAndLookAsTheirTwoSidesDid) {
    // Leaves are double-sided: each triangle is in the mesh once per side, and the LOD4 pass drew
    // both, the GL culling the one facing away. It now draws one, unculled, with the colour of
    // the side in view (lod/shape_geometry.h). The golden is the image of the old way, from
    // under the trees, where leaves show both sides, lit per pixel: LOD4 is now lit per vertex,
    // which shades the round bark and twigs a little differently (47 dB against the golden);
    // leaves lit from the wrong side would be 33 dB.
    auto [city, impostors] = park();
    scene::LodProfile lod;
    lod.treeGeometricError = 0.0; // every tree as geometry
    // Under the first tree's crown, looking up through it.
    glm::dvec2 trunk(0.0);
    const std::vector<glm::dvec2>& footprint =
        city.catalog->scene().treeGrammars.at(0).buildings.at(0).footprint;
    for (const glm::dvec2& corner : footprint) trunk += corner / double(footprint.size());
    const scene::CameraPose pose =
        lookAt({trunk.x - 5.0, trunk.y - 4.0, 16.0}, {trunk.x, trunk.y, 6.0}, 60.0);
    const Rendered r = render(city, impostors, RenderMode::Lod, pose, 1, 1, true, lod);
    EXPECT_GT(r.stats.terminalsPerLod[4], 1000u);
    EXPECT_EQ(r.stats.treeBillboards, 0u);
    EXPECT_GT(coverage(r.image), 0.3);
    expectGolden(r.image, "park_tree_parts", 44.0);
}

TEST_F(CityRendererTest, HiddenImpostorsAndBillboardsAreDroppedWithoutChangingAPixel) {
    // At street level most far trees and facades stand behind the blocks in front of them.
    testing::TestCity city = testing::makeCity(50, 200);
    const SceneImpostors impostors = bake(city);
    const scene::CameraPose pose = lookAt({-200, -230, 2}, {0, 0, 4});
    for (uint32_t samples : {1u, 4u}) {
        // Forced LOD1: base volumes and billboards; forced LOD3: LOD3 terminals and billboards.
        for (RenderMode mode : {RenderMode::AllLod1, RenderMode::AllLod3}) {
            Rendered all = render(city, impostors, mode, pose, 1, samples, false);
            Rendered culled = render(city, impostors, mode, pose, 1, samples, true);
            const std::string what =
                std::string(renderModeName(mode)) + ", " + std::to_string(samples) + " samples";
            EXPECT_EQ(all.stats.treeBillboardsOccluded + all.stats.lod3Occluded +
                          all.stats.cullOccludedTerminals,
                      0u)
                << what;
            EXPECT_GT(culled.stats.treeBillboardsOccluded, 0u) << what;
            EXPECT_LT(culled.stats.treeBillboardsOccluded, culled.stats.treeBillboards) << what;
            if (mode == RenderMode::AllLod3) {
                // The cull pass drops the terminals the base volumes hide, the LOD3 pass more
                // of those the impostors drawn before them hide.
                EXPECT_GT(culled.stats.cullOccludedTerminals, 0u) << what;
                EXPECT_GT(culled.stats.lod3Occluded, 0u) << what;
                EXPECT_LT(culled.stats.lod3Occluded, culled.stats.terminalsPerLod[3]) << what;
            }
            std::printf("%s: %lu terminals culled as hidden; %u of %u billboards and %u of %lu LOD3 "
                        "terminals dropped\n",
                        what.c_str(), culled.stats.cullOccludedTerminals, culled.stats.treeBillboardsOccluded,
                        culled.stats.treeBillboards, culled.stats.lod3Occluded,
                        culled.stats.terminalsPerLod[3]);
            EXPECT_EQ(culled.image.pixels, all.image.pixels) << what;
        }
    }
}

TEST_F(CityRendererTest, BillboardsBeyondLod2AreFlatAndShowTheSameTrees) {
    // At street level, base volumes only (forced LOD1) and every tree a billboard: with LOD2's
    // error tiny every billboard lies beyond LOD2's distance and takes the flat form (the
    // nearest view on the billboard's plane, which the GL depth-tests before shading), with it
    // huge every one takes the blended form (four views, writing the depth it finds). The
    // two show the same trees; they are not the same pixels, so each form did draw. (llvmpipe
    // counts a fragment shader invocation before its depth test, so the fragments the flat
    // form leaves unshaded do not show in ARB_pipeline_statistics_query; docs/BENCHMARKS.md
    // has their time.)
    testing::TestCity city = testing::makeCity(50, 200);
    const SceneImpostors impostors = bake(city);
    const scene::CameraPose pose = lookAt({-200, -230, 2}, {0, 0, 4});
    Rendered frames[2]; // flat, blended
    for (int i = 0; i < 2; ++i) {
        scene::LodProfile lod;
        lod.geometricError[2] = i == 1 ? 1e4 : 1e-3;
        frames[i] = render(city, impostors, RenderMode::AllLod1, pose, 1, 1, true, lod);
    }
    ASSERT_GT(frames[0].stats.treeBillboards, 0u);
    EXPECT_EQ(frames[1].stats.treeBillboards, frames[0].stats.treeBillboards);
    EXPECT_EQ(frames[1].stats.treeBillboardsOccluded, frames[0].stats.treeBillboardsOccluded);
    const double psnr = render::compareImages(frames[0].image, frames[1].image).psnr;
    std::printf("flat billboards against blended: %.1f dB\n", psnr);
    EXPECT_NE(frames[0].image.pixels, frames[1].image.pixels);
    EXPECT_GT(psnr, 40.0);
}

TEST_F(CityRendererTest, FarBaseVolumesAndBuildingsTheNearOnesHideAreNotDrawnAndNoPixelChanges) {
    // At street level, with LOD0 claiming 1 m so that the cells within 42 m form the first
    // ring of volumes: the block in front hides half the far cells' volumes, drawn at LOD0 or
    // ray-cast at LOD1, and those are never built.
    testing::TestCity city = testing::makeCity(200, 0);
    const SceneImpostors impostors = bake(city);
    const scene::CameraPose pose = lookAt({-100, -51, 2}, {300, 0, 4});
    scene::LodProfile lod;
    lod.geometricError[0] = 1.0;
    for (RenderMode mode : {RenderMode::AllLod0, RenderMode::AllLod1}) {
        for (uint32_t samples : {1u, 4u}) {
            const std::string what =
                std::string(renderModeName(mode)) + ", " + std::to_string(samples) + " samples";
            Rendered all = render(city, impostors, mode, pose, 1, samples, false, lod);
            Rendered culled = render(city, impostors, mode, pose, 1, samples, true, lod);
            EXPECT_EQ(all.stats.volumesOccluded, 0u) << what;
            EXPECT_EQ(all.stats.volumeBuildingsOccluded, 0u) << what;
            EXPECT_GT(culled.stats.volumesOccluded, 0u) << what;
            // Of the batches that show, some buildings do not: those are left out one by one.
            EXPECT_GT(culled.stats.volumeBuildingsOccluded, 0u) << what;
            EXPECT_LT(culled.stats.volumesOccluded, culled.stats.batchesDrawn) << what;
            EXPECT_LT(culled.stats.triangles, all.stats.triangles) << what;
            // A hidden batch is not even built: the test used its cell's bounds.
            EXPECT_EQ(all.stats.volumesBuilt, all.stats.batchesDrawn) << what;
            EXPECT_EQ(culled.stats.volumesBuilt + culled.stats.volumesOccluded, all.stats.volumesBuilt)
                << what;
            std::printf("%s: %u of %u batches' volumes hidden, and %u buildings of the others; %llu of %llu "
                        "triangles drawn\n",
                        what.c_str(), culled.stats.volumesOccluded, culled.stats.batchesDrawn,
                        culled.stats.volumeBuildingsOccluded,
                        static_cast<unsigned long long>(culled.stats.triangles),
                        static_cast<unsigned long long>(all.stats.triangles));
            EXPECT_EQ(culled.image.pixels, all.image.pixels) << what;
        }
    }
}

TEST_F(CityRendererTest, BuildingsAPixelOrTwoAcrossArePointsThatLookAsTheirShellsForNoTriangles) {
    // The city from 2 km, its buildings (20 to 40 m across) one to three pixels: under the
    // point size (twice the default 2 px error bound). Four samples, so that a point's
    // coverage counts as a shell's would.
    testing::TestCity city = testing::makeCity(200, 0);
    const SceneImpostors impostors = bake(city);
    const scene::CameraPose pose = lookAt({-1400, -1400, 500}, {0, 0, 0});
    Rendered reference = render(city, impostors, RenderMode::AllLod4, pose, 1, 4);
    Rendered points = render(city, impostors, RenderMode::Lod, pose, 1, 4);
    Rendered shells = render(city, impostors, RenderMode::Lod, pose, 1, 4, true, {}, 2.0, true, 0.0);
    EXPECT_EQ(shells.stats.volumeBuildingPoints, 0u);
    EXPECT_GT(points.stats.volumeBuildingPoints, 100u);
    EXPECT_LT(points.stats.triangles, shells.stats.triangles / 4);
    EXPECT_GT(coverage(points.image), 0.5 * coverage(shells.image));
    const double pointError = render::compareImages(points.image, reference.image).psnr,
                 shellError = render::compareImages(shells.image, reference.image).psnr,
                 apart = render::compareImages(points.image, shells.image).psnr;
    std::printf("%u buildings as points, %llu triangles against %llu; against LOD4: points %.2f dB, shells "
                "%.2f dB; points against shells %.2f dB\n",
                points.stats.volumeBuildingPoints, static_cast<unsigned long long>(points.stats.triangles),
                static_cast<unsigned long long>(shells.stats.triangles), pointError, shellError, apart);
    EXPECT_GT(pointError, shellError - 1.0);
    EXPECT_GT(apart, 30.0);
    // Nearer, the same buildings are shells again.
    Rendered near = render(city, impostors, RenderMode::Lod, lookAt({-300, -300, 120}, {0, 0, 0}), 1, 4);
    EXPECT_LT(near.stats.volumeBuildingPoints, points.stats.volumeBuildingPoints / 4);
}

TEST_F(CityRendererTest, FarWallsShadedAtTheirMeanPerVertexLookAsTheirTexture) {
    // The city from 2 km as shells (no points): every LOD0 batch lies beyond the depth where
    // the wall texture is its mean (about 190 m at 96 pixels high).
    testing::TestCity city = testing::makeCity(200, 0);
    const SceneImpostors impostors = bake(city);
    const scene::CameraPose far = lookAt({-1400, -1400, 500}, {0, 0, 0});
    Rendered mean = render(city, impostors, RenderMode::Lod, far, 1, 1, true, {}, 2.0, true, 0.0);
    Rendered textured = render(city, impostors, RenderMode::Lod, far, 1, 1, true, {}, 2.0, true, 0.0, false);
    EXPECT_GT(mean.stats.volumesShadedAtMean, 0u);
    EXPECT_EQ(textured.stats.volumesShadedAtMean, 0u);
    EXPECT_EQ(mean.stats.triangles, textured.stats.triangles);
    EXPECT_GT(coverage(mean.image), 0.01);
    const render::ImageDifference apart = render::compareImages(mean.image, textured.image);
    std::printf("%u batches shaded at the mean: %.1f dB from the texture\n", mean.stats.volumesShadedAtMean,
                apart.psnr);
    EXPECT_GT(apart.psnr, 50.0); // the fog per vertex, not per pixel, is the only difference
    // From the city's edge, the batches around the camera keep their texture.
    Rendered near = render(city, impostors, RenderMode::Lod, lookAt({-300, -300, 60}, {0, 0, 0}));
    EXPECT_LT(near.stats.volumesShadedAtMean, mean.stats.volumesShadedAtMean);
}

TEST_F(CityRendererTest, ACityFarFromTheOriginRendersAsAtTheOrigin) {
    testing::TestCity near = testing::makeCity(30, 20);
    testing::TestCity far = testing::makeCity(30, 20, "[10000000, -10000000, 0]");
    const glm::dvec3 offset(1e7, -1e7, 0.0);
    const scene::CameraPose pose = lookAt({-150, -180, 30}, {0, 0, 10});
    scene::CameraPose farPose = pose;
    farPose.position += offset;
    const SceneImpostors nearImpostors = bake(near), farImpostors = bake(far);
    Rendered a = render(near, nearImpostors, RenderMode::Lod, pose);
    Rendered b = render(far, farImpostors, RenderMode::Lod, farPose);
    // The hexagonal grid is anchored at the world origin, so the far city falls into other
    // cells, whose LOD switches lie elsewhere: close, not identical.
    const double psnr = render::compareImages(a.image, b.image).psnr;
    std::printf("1e7 m out against the origin: %.1f dB\n", psnr);
    EXPECT_GE(psnr, 30.0) << "the city 1e7 m out renders differently";
}

TEST_F(CityRendererTest, OddCamerasRenderWithoutError) {
    testing::TestCity city = testing::makeCity(30, 20);
    const SceneImpostors impostors = bake(city);
    // Inside the first building (its footprint's centroid, half way up).
    const grammar::BuildingInput& inside = city.catalog->scene().buildingGrammars[1].buildings.front();
    glm::dvec2 centre(0.0);
    for (const glm::dvec2& p : inside.footprint) centre += p;
    centre /= double(inside.footprint.size());
    for (const scene::CameraPose& pose :
         {lookAt({centre.x, centre.y, 4.0}, {centre.x + 10, centre.y, 4.0}),
          lookAt({-150, -180, 30}, {0, 0, 10}, 1.0), lookAt({-150, -180, 30}, {0, 0, 10}, 179.0),
          lookAt({0, 0, 500}, {0, 0, 0})}) {
        Rendered r = render(city, impostors, RenderMode::Lod, pose, 2);
        EXPECT_TRUE(std::isfinite(r.stats.frameMs));
        for (float v : r.image.pixels) ASSERT_TRUE(std::isfinite(v));
    }
}

} // namespace
} // namespace hexlod::lod
