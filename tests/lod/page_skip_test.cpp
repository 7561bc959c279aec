// Pages of terminals skipped whole before the GPU pass reads them: facing away from the camera
// (their walls' planes; never a tree's parts, which no wall hides) or holding only parts of
// trees drawn as billboards. A skipped page must
// hold nothing the pass would have drawn, so the tests hold the page tests to the terminal
// tests they stand in for, and the GPU pass with skipping to the CPU reference without.
#include "../render/gl_fixture.h"
#include "cull_lists.h"

#include "hexlod/lod/cpu_cull.h"
#include "hexlod/lod/gpu_cull.h"
#include "hexlod/lod/page_bounds.h"
#include "hexlod/lod/terminal_arena.h"
#include "hexlod/render/gl_api.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <tuple>

namespace hexlod::lod {
namespace {

using grammar::TerminalRecord;
using grammar::TerminalSet;

// The outward normal of wall `wall` (0: -y, 1: +x, 2: +y, 3: -x) of a square footprint.
glm::vec3 wallNormal(uint32_t wall) {
    const glm::vec3 normals[4] = {{0, -1, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}};
    return normals[wall % 4];
}

// A facade part on wall `wall` of a `side` m square footprint centred at `centre`, `along` of
// the way along the wall and `height` m up: its axes as a facade's (x along the wall, y up, z
// out of it).
TerminalRecord wallPart(glm::vec2 centre, float side, uint32_t wall, float along, float height,
                        glm::vec2 size, float depthRatio, uint16_t shape, uint32_t building) {
    const glm::vec3 z = wallNormal(wall), y(0, 0, 1), x = glm::cross(y, z);
    const glm::vec3 corner = glm::vec3(centre, height) + z * (0.5f * side) + x * ((along - 0.5f) * side);
    return grammar::packTerminal(corner, x, y, z, size, depthRatio, shape, building);
}

// A set from records, sorted by shape and then building as a grammar's sets are; the records
// of one building keep their order.
TerminalSet setOf(std::vector<TerminalRecord> records, uint32_t shapes) {
    std::stable_sort(records.begin(), records.end(), [](const TerminalRecord& a, const TerminalRecord& b) {
        return std::tuple(a.shapeAndDepth & 0xffffu, a.building) <
               std::tuple(b.shapeAndDepth & 0xffffu, b.building);
    });
    TerminalSet set;
    set.countPerShape.assign(shapes, 0);
    for (const TerminalRecord& r : records) ++set.countPerShape[r.shapeAndDepth & 0xffffu];
    set.records.assign(records.begin(), records.end());
    return set;
}

// `buildings` buildings of 20 m square within `extent` m of the cell origin, each wall's parts
// of one of `shapes` shapes, each building's parts wall by wall.
TerminalSet buildingSet(std::mt19937& random, uint32_t buildings, uint32_t shapes, float extent) {
    std::uniform_real_distribution<float> place(-extent, extent), unit(0.0f, 1.0f), size(0.5f, 3.0f);
    std::uniform_int_distribution<uint32_t> parts(10, 120), shape(0, shapes - 1);
    std::vector<TerminalRecord> records;
    for (uint32_t b = 0; b < buildings; ++b) {
        const glm::vec2 centre(place(random), place(random));
        for (uint32_t wall = 0; wall < 4; ++wall) {
            const uint16_t wallShape = uint16_t(shape(random));
            for (uint32_t i = parts(random); i > 0; --i)
                records.push_back(wallPart(centre, 20.0f, wall, unit(random), 40.0f * unit(random),
                                           glm::vec2(size(random), size(random)), 0.5f * unit(random),
                                           wallShape, b));
        }
    }
    return setOf(std::move(records), shapes);
}

// Trees `firstTree` to `firstTree + count - 1`, rooted at random places within `extent` m of the
// origin (written to `trees`, by id): leaves (shape 0), a trunk (1) and branches (2) around
// each root, each part's building id its tree's.
TerminalSet treeSet(std::mt19937& random, uint32_t firstTree, uint32_t count, float extent,
                    std::vector<glm::vec4>& trees) {
    std::uniform_real_distribution<float> place(-extent, extent), unit(-1.0f, 1.0f), size(0.2f, 1.5f);
    std::uniform_int_distribution<uint32_t> leaves(30, 150), branches(0, 6);
    std::vector<TerminalRecord> records;
    trees.resize(std::max<size_t>(trees.size(), firstTree + count));
    auto part = [&](glm::vec3 at, uint16_t shape, uint32_t tree) {
        const glm::mat3 axes =
            glm::mat3_cast(glm::normalize(glm::quat(unit(random), unit(random), unit(random), unit(random))));
        records.push_back(
            grammar::packTerminal(at, axes[0], axes[1], axes[2], glm::vec2(size(random)), 0.3f, shape, tree));
    };
    for (uint32_t tree = firstTree; tree < firstTree + count; ++tree) {
        const glm::vec3 root(place(random), place(random), 0.0f);
        trees[tree] = glm::vec4(root, 0.0f);
        part(root, 1, tree);
        for (uint32_t i = branches(random); i > 0; --i)
            part(root + glm::vec3(0, 0, 3.0f + unit(random)), 2, tree);
        for (uint32_t i = leaves(random); i > 0; --i)
            part(root + glm::vec3(4.0f * unit(random), 4.0f * unit(random), 6.0f + 3.0f * unit(random)), 0,
                 tree);
    }
    return setOf(std::move(records), 3);
}

// classifyTerminal's decision for a record of a batch whose origin minus the camera is `origin`.
uint32_t classify(const TerminalRecord& record, const glm::vec3& origin, const shared::CullFrame& frame) {
    gpu::GpuTerminal t;
    std::memcpy(&t, &record, sizeof t);
    float transition;
    glm::vec4 sphere;
    return shared::classifyTerminal(t, t.position + origin, frame, false, true, transition, sphere);
}

// Its backface test alone: a frame whose planes pass everything and that has no LOD distances.
bool backfaceCulled(const TerminalRecord& record, const glm::vec3& origin) {
    return classify(record, origin, shared::CullFrame{}) == HEXLOD_CULLED;
}

TEST(PageBoundsTest, EachPageOfALargeSetIsBoundedAsItsRecordsAloneAre) {
    // Thousands of pages: the pages are computed in parallel, in chunks.
    std::mt19937 random(11);
    const TerminalSet set = buildingSet(random, 400, 5, 300.0f);
    const std::vector<PageBounds> pages = pageBounds(set);
    ASSERT_EQ(pages.size(), (set.records.size() + kArenaPageRecords - 1) / kArenaPageRecords);
    ASSERT_GT(pages.size(), 1000u);
    for (size_t p = 0; p < pages.size(); ++p) {
        TerminalSet alone;
        const size_t first = p * kArenaPageRecords;
        alone.records.assign(set.records.begin() + first,
                             set.records.begin() + std::min(set.records.size(), first + kArenaPageRecords));
        const std::vector<PageBounds> one = pageBounds(alone);
        ASSERT_EQ(one.size(), 1u);
        const PageBounds &got = pages[p], &want = one[0];
        EXPECT_EQ(got.sphere, want.sphere) << "page " << p;
        EXPECT_EQ(got.boxMin, want.boxMin) << "page " << p;
        EXPECT_EQ(got.boxMax, want.boxMax) << "page " << p;
        ASSERT_EQ(got.faceCount, want.faceCount) << "page " << p;
        for (uint32_t f = 0; f < got.faceCount; ++f) EXPECT_EQ(got.faces[f], want.faces[f]) << "page " << p;
        EXPECT_EQ(got.firstBuilding, want.firstBuilding) << "page " << p;
        EXPECT_EQ(got.lastBuilding, want.lastBuilding) << "page " << p;
    }
    EXPECT_TRUE(pageBounds(TerminalSet{}).empty());
}

TEST(PageBoundsTest, APageFacesAwayOnlyWhenTheCameraIsBehindEachOfItsWalls) {
    // One page: 40 windows on the south wall (y = -10) and 24 on the east wall (x = 10) of a
    // 20 m building, 2 m square and 0.5 m deep.
    std::vector<TerminalRecord> records;
    for (uint32_t i = 0; i < 64; ++i)
        records.push_back(wallPart(glm::vec2(0.0f), 20.0f, i < 40 ? 0 : 1, float(i % 8) / 8.0f,
                                   float(i / 8) * 3.0f, glm::vec2(2.0f), 0.25f, 0, 7));
    const TerminalSet set = setOf(records, 1);
    const std::vector<PageBounds> pages = pageBounds(set);
    ASSERT_EQ(pages.size(), 1u);
    EXPECT_EQ(pages[0].faceCount, 2u);
    EXPECT_EQ(pages[0].firstBuilding, 7u);
    EXPECT_EQ(pages[0].lastBuilding, 7u);
    // The cell origin at 0: a batch's origin minus the camera is minus the camera.
    const auto facesAway = [&](glm::vec3 camera) { return pageFacesAway(pages[0], -camera); };
    EXPECT_FALSE(facesAway({0, -30, 2}));   // in front of the south wall
    EXPECT_FALSE(facesAway({30, 0, 2}));    // in front of the east wall
    EXPECT_TRUE(facesAway({0, 0, 2}));      // inside: behind both
    EXPECT_TRUE(facesAway({9, 0, 2}));      // a metre behind the east wall
    EXPECT_FALSE(facesAway({9.6f, 0, 2}));  // behind its plane, within the windows' depth
    EXPECT_FALSE(facesAway({0, -9.6f, 2})); // the same at the south wall
    // A page of the south wall's windows alone faces away from the east side too.
    const std::vector<PageBounds> south =
        pageBounds(setOf(std::vector<TerminalRecord>(records.begin(), records.begin() + 40), 1));
    ASSERT_EQ(south[0].faceCount, 1u);
    EXPECT_TRUE(pageFacesAway(south[0], -glm::vec3(30, 0, 2)));
    EXPECT_FALSE(pageFacesAway(south[0], -glm::vec3(30, -30, 2)));
}

TEST(PageBoundsTest, MoreWallsThanAPageHoldsOrANonFiniteRecordGiveNoFaces) {
    std::vector<TerminalRecord> records;
    for (uint32_t i = 0; i < 30; ++i)
        records.push_back(
            wallPart(glm::vec2(0.0f), 20.0f, i % 3, 0.5f, float(i), glm::vec2(2.0f), 0.25f, 0, i));
    const std::vector<PageBounds> three = pageBounds(setOf(records, 1));
    EXPECT_EQ(three[0].faceCount, 0u);
    EXPECT_FALSE(pageFacesAway(three[0], glm::vec3(0.0f))); // from inside, behind all three walls
    EXPECT_EQ(three[0].firstBuilding, 0u);
    EXPECT_EQ(three[0].lastBuilding, 29u);
    records.resize(10); // walls 0, 1 and 2 still
    records.erase(std::remove_if(records.begin(), records.end(),
                                 [](const TerminalRecord& r) { return r.building % 3 == 2; }),
                  records.end());
    records[3].position[1] = NAN;
    const std::vector<PageBounds> broken = pageBounds(setOf(records, 1));
    EXPECT_EQ(broken[0].faceCount, 0u);
    EXPECT_TRUE(std::isinf(broken[0].sphere.w));
    EXPECT_FALSE(pageFacesAway(broken[0], glm::vec3(0.0f)));
}

// Random pages of one or two walls, far from the world origin, from random cameras: a page
// faces away only when each of its terminals is backface culled, and does so nearly whenever
// they all are (the slack for float rounding is small).
TEST(PageBoundsTest, FacingAwayIsNeverStricterThanTheTerminalsOwnTest) {
    std::mt19937 random(77);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), size(0.3f, 6.0f);
    std::uniform_real_distribution<double> place(-400.0, 400.0), near(-60.0, 60.0);
    uint64_t facingAway = 0, allCulled = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const glm::dvec3 cellOrigin(1e7 * (trial % 2), -3e6 * (trial % 3), 20.0);
        const glm::vec2 centre(place(random), place(random));
        const uint32_t firstWall = trial % 4, walls = 1 + trial % 2;
        std::vector<TerminalRecord> records;
        for (uint32_t i = 0; i < 64; ++i)
            records.push_back(wallPart(centre, 5.0f + 40.0f * unit(random), firstWall + i % walls,
                                       unit(random), 50.0f * unit(random),
                                       glm::vec2(size(random), size(random)), 2.0f * unit(random), 0, 0));
        const PageBounds page = pageBounds(setOf(records, 1))[0];
        ASSERT_EQ(page.faceCount, walls);
        const glm::dvec3 camera =
            cellOrigin + glm::dvec3(centre, 0.0) + glm::dvec3(near(random), near(random), 2.0);
        const glm::vec3 origin(cellOrigin - camera); // as the pass receives it
        const bool culled = std::all_of(records.begin(), records.end(),
                                        [&](const TerminalRecord& r) { return backfaceCulled(r, origin); });
        if (pageFacesAway(page, origin)) {
            ++facingAway;
            EXPECT_TRUE(culled) << "trial " << trial;
        }
        allCulled += culled;
    }
    EXPECT_GT(facingAway, 300u);
    EXPECT_GE(double(facingAway), 0.95 * double(allCulled));
}

// Random pages of one or two walls, far from the world origin, against random frustums: a page
// is outside only when classifyTerminal culls each of its terminals, and its box finds pages
// outside that its sphere cannot (a wall's page is a thin slab).
TEST(PageBoundsTest, APageIsOutsideTheFrustumOnlyWhenEachOfItsTerminalsIs) {
    std::mt19937 random(78);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), size(0.3f, 6.0f);
    std::uniform_real_distribution<double> place(-400.0, 400.0), near(-80.0, 80.0), heading(0.0, 6.283);
    uint64_t outside = 0, byBoxAlone = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const glm::dvec3 cellOrigin(1e7 * (trial % 2), -3e6 * (trial % 3), 20.0);
        const glm::vec2 centre(place(random), place(random));
        std::vector<TerminalRecord> records;
        for (uint32_t i = 0; i < 64; ++i)
            records.push_back(wallPart(centre, 5.0f + 40.0f * unit(random), trial % 4 + i % (1 + trial % 2),
                                       unit(random), 50.0f * unit(random),
                                       glm::vec2(size(random), size(random)), 2.0f * unit(random), 0, 0));
        const PageBounds page = pageBounds(setOf(records, 1))[0];
        const glm::dvec3 camera =
            cellOrigin + glm::dvec3(centre, 0.0) + glm::dvec3(near(random), near(random), 2.0);
        const double a = heading(random);
        const cells::Frustum frustum(camera, glm::dvec3(std::cos(a), std::sin(a), 0.1), glm::dvec3(0, 0, 1),
                                     0.5, 16.0 / 9.0, 0.5, 2000.0);
        shared::CullFrame frame = makeCullFrame(frustum, scene::LodProfile{}, 0.5, 720, 0.2, false);
        const glm::vec3 origin(cellOrigin - camera);
        if (pageMayBeVisible(page, origin, frame)) continue;
        ++outside;
        byBoxAlone += pageMayBeVisible(page.sphere, origin, frame);
        for (const TerminalRecord& record : records)
            EXPECT_EQ(classify(record, origin, frame), HEXLOD_CULLED) << "trial " << trial;
    }
    EXPECT_GT(outside, 1000u);
    EXPECT_GT(byBoxAlone, 100u);
}

// The parts of a tree stand free: from behind the plane a part recedes to, its other side
// shows (a leaf's back, a branch's far side), where a wall would hide a facade's. The same
// page of parts facing one way, seen from behind, as a building's and as a tree's.
TEST(PageBoundsTest, PartsOfTreesAreNotCulledForFacingAwayAsAWallsAre) {
    std::vector<TerminalRecord> records;
    std::vector<glm::vec4> trees = {{0, 0, 0, 0}};
    for (uint32_t i = 0; i < 64; ++i)
        records.push_back(wallPart(glm::vec2(0.0f), 4.0f, 0, float(i % 8) / 8.0f, 2.0f + float(i / 8) * 0.5f,
                                   glm::vec2(0.4f), 0.3f, 0, 0));
    const TerminalSet set = setOf(records, 1);
    const std::vector<PageBounds> bounds = pageBounds(set);
    ASSERT_EQ(bounds[0].faceCount, 1u);
    CullInputs inputs;
    inputs.shapeCount = 1;
    inputs.shapeImpostor = {0};
    inputs.trees = &trees;
    inputs.camera = glm::dvec3(0.0, 10.0, 3.0); // behind the parts, which face -y
    inputs.batches.push_back({&set, nullptr, glm::dvec3(0.0), 0, &bounds});
    const cells::Frustum frustum(inputs.camera, glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1), 1.0, 1.5, 0.1,
                                 5000.0);
    inputs.frame = makeCullFrame(frustum, scene::LodProfile{}, 1.0, 720, 0.2, false);
    for (uint8_t tree : {0, 1}) {
        inputs.shapeTree = {tree};
        const CullPages pages = selectCullPages(inputs);
        EXPECT_EQ(pages.facingAwayTerminals, tree ? 0u : 64u);
        const CullResult culled = cullOnCpu(inputs);
        EXPECT_EQ(culled.terminalsPerLod[HEXLOD_LOD4], tree ? 64u : 0u);
        EXPECT_EQ(culled.culled, tree ? 0u : 64u);
    }
}

// selectCullPages over one tree batch: leaves a page per tree (trees 0 to 2), then the trunks
// of all three in one page.
TEST(PageBoundsTest, APageOfTreesIsSkippedOnlyWhenEachTreeItSpansIsABillboard) {
    std::vector<TerminalRecord> records;
    std::vector<glm::vec4> trees = {{0, 20, 0, 0}, {0, 200, 0, 0}, {0, 300, 0, 0}};
    for (uint32_t tree = 0; tree < 3; ++tree) {
        records.push_back(
            wallPart(glm::vec2(trees[tree]), 1.0f, 0, 0.5f, 0.0f, glm::vec2(1.0f), 0.3f, 1, tree));
        for (uint32_t i = 0; i < 64; ++i)
            records.push_back(
                wallPart(glm::vec2(trees[tree]), 4.0f, i % 4, 0.5f, 6.0f, glm::vec2(1.0f), 0.3f, 0, tree));
    }
    const TerminalSet set = setOf(records, 2);
    const std::vector<PageBounds> bounds = pageBounds(set);
    ASSERT_EQ(bounds.size(), 4u);
    CullInputs inputs;
    inputs.shapeCount = 2;
    inputs.shapeImpostor = {0, 0};
    inputs.shapeTree = {1, 1};
    inputs.trees = &trees;
    inputs.camera = glm::dvec3(0.0, 0.0, 1.7);
    inputs.batches.push_back({&set, nullptr, glm::dvec3(0.0), 0, &bounds});
    const cells::Frustum frustum(inputs.camera, glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1), 1.0, 1.5, 0.1,
                                 5000.0);
    inputs.frame = makeCullFrame(frustum, scene::LodProfile{}, 1.0, 720, 0.2, false);
    const auto skipped = [&](double cut) {
        setTreeCut(inputs.frame, cut, glm::dvec3(0.0), inputs.camera);
        return selectCullPages(inputs).billboardTerminals;
    };
    EXPECT_EQ(skipped(100.0), 128u); // trees 1 and 2 beyond the cut: their leaves' pages
    EXPECT_EQ(skipped(10.0), 195u);  // every tree beyond it: the trunks' page too
    EXPECT_EQ(skipped(250.0), 64u);  // tree 2 alone
    EXPECT_EQ(skipped(-1.0), 0u);    // no billboards
    // A page that spans more tree ids than a page holds records is not tested id by id, and a
    // page that holds other shapes is never skipped for its trees.
    trees.resize(200, glm::vec4(0, 500, 0, 0));
    std::vector<TerminalRecord> wide = {records[0], records[65]};
    wide[1].building = 150;
    const TerminalSet wideSet = setOf(wide, 2);
    const std::vector<PageBounds> wideBounds = pageBounds(wideSet);
    inputs.batches = {{&wideSet, nullptr, glm::dvec3(0.0), 0, &wideBounds}};
    EXPECT_EQ(skipped(10.0), 0u);
    inputs.shapeTree = {1, 0};
    inputs.batches = {{&set, nullptr, glm::dvec3(0.0), 0, &bounds}};
    EXPECT_EQ(skipped(10.0), 192u); // the leaves' pages; the trunks are not tree parts now
}

class PageSkipTest : public render::GlTest {};

// City-like batches (buildings' parts wall by wall; trees' parts tree by tree) from cameras in
// the streets: the pass skips pages facing away and pages of billboard trees, and its lists
// match the reference, which reads every terminal.
TEST_F(PageSkipTest, PagesSkippedWholeHoldNothingThePassWouldDraw) {
    GpuCull cull;
    std::string error;
    ASSERT_TRUE(cull.init(error)) << error;
    TerminalArena arena;
    ASSERT_TRUE(arena.create(1 << 17, error)) << error;
    std::mt19937 random(5);
    // Shapes 0 to 3: a building grammar's (0 and 1 with impostors); 4 to 6: a tree grammar's.
    const uint32_t buildingShapes = 4, treeBase = buildingShapes;
    std::vector<TerminalSet> sets;
    std::vector<glm::vec4> trees;
    for (int b = 0; b < 4; ++b) sets.push_back(buildingSet(random, 40, buildingShapes, 150.0f));
    for (uint32_t b = 0; b < 2; ++b) sets.push_back(treeSet(random, 120 * b, 120, 150.0f, trees));
    uint32_t treeBuffer = 0;
    gl::glCreateBuffers(1, &treeBuffer);
    gl::glNamedBufferStorage(treeBuffer, GLsizeiptr(trees.size() * sizeof(glm::vec4)), trees.data(), 0);
    uint64_t facingAway = 0, billboards = 0, treeEntries = 0, visible = 0;
    for (int trial = 0; trial < 8; ++trial) {
        arena.beginFrame(trial);
        CullInputs inputs;
        inputs.shapeCount = buildingShapes + 3;
        inputs.shapeImpostor = {1, 1, 0, 0, 0, 0, 0};
        inputs.shapeTree = {0, 0, 0, 0, 1, 1, 1};
        inputs.trees = &trees;
        inputs.treeBuffer = treeBuffer;
        // Every batch in one cell; far from the world origin in odd trials.
        const glm::dvec3 cellOrigin(1e7 * (trial % 2), -3e6 * (trial % 2), 10.0);
        std::uniform_real_distribution<double> street(-120.0, 120.0), heading(0.0, 6.283);
        inputs.camera = cellOrigin + glm::dvec3(street(random), street(random), trial < 4 ? 1.7 : 35.0);
        for (size_t b = 0; b < sets.size(); ++b) {
            const ArenaBatch* resident = arena.acquire(b, sets[b]);
            ASSERT_TRUE(resident);
            inputs.batches.push_back(
                {&sets[b], &resident->pages, cellOrigin, b < 4 ? 0u : treeBase, &resident->bounds});
        }
        const double a = heading(random), fovY = 0.8;
        const cells::Frustum frustum(inputs.camera, glm::dvec3(std::cos(a), std::sin(a), -0.05),
                                     glm::dvec3(0, 0, 1), fovY, 16.0 / 9.0, 0.5, 2000.0);
        scene::LodProfile profile;
        inputs.frame = makeCullFrame(frustum, profile, fovY, 720, 0.2, true);
        setTreeCut(inputs.frame, 60.0, cellOrigin, inputs.camera);

        const CullResult reference = cullOnCpu(inputs);
        cull.run(inputs, arena.buffer(),
                 std::vector<MeshDrawInfo>(inputs.shapeCount, MeshDrawInfo{36, 0, 0}));
        const std::vector<glm::uvec4> counters = cull.readCounters();
        const std::vector<gpu::GpuTerminal> lists = cull.readLists(), lod3Lists = cull.readLod3Lists();
        const DrawListLayout& layout = cull.layout();
        for (uint32_t s = 0; s < inputs.shapeCount; ++s) {
            const std::vector<ListEntryId> lod3 = sortedIds(reference.impostor[s], HEXLOD_LOD3),
                                           lod2 = sortedIds(reference.impostor[s], HEXLOD_LOD2);
            ASSERT_EQ(counters[s].x, reference.lod4[s].size()) << "shape " << s << " trial " << trial;
            ASSERT_EQ(counters[s].z, lod3.size()) << "shape " << s << " trial " << trial;
            ASSERT_EQ(counters[s].w, lod2.size()) << "shape " << s << " trial " << trial;
            EXPECT_EQ(sortedIds(lists, layout.base[s], counters[s].x), sortedIds(reference.lod4[s], 0));
            EXPECT_EQ(sortedIds(lists, layout.base[s] + layout.capacity[s] - counters[s].w, counters[s].w),
                      lod2);
            EXPECT_EQ(sortedIds(lod3Lists, layout.lod3Base[s], counters[s].z), lod3);
            visible += counters[s].x + counters[s].z + counters[s].w;
            if (inputs.shapeTree[s]) treeEntries += counters[s].x;
        }
        const GpuCull::PageStats pages = cull.pageStats();
        EXPECT_LE(pages.skippedTerminals, reference.culled);
        facingAway += pages.facingAwayTerminals;
        billboards += pages.billboardTerminals;
    }
    gl::glDeleteBuffers(1, &treeBuffer);
    // Each kind of skip happened, and trees near the cameras were still drawn as geometry.
    EXPECT_GT(facingAway, 5000u);
    EXPECT_GT(billboards, 5000u);
    EXPECT_GT(treeEntries, 0u);
    EXPECT_GT(visible, 0u);
}

} // namespace
} // namespace hexlod::lod
