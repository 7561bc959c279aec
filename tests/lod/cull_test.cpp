// The GPU cull and LOD pass against its CPU reference: identical visible sets and LOD choices
// on random terminals and cameras, and the culling rules themselves on hand-placed terminals.
#include "../render/gl_fixture.h"
#include "cull_lists.h"

#include "hexlod/lod/cpu_cull.h"
#include "hexlod/lod/gpu_cull.h"
#include "hexlod/lod/page_bounds.h"
#include "hexlod/lod/prepared_page_bounds.h"
#include "hexlod/lod/terminal_arena.h"
#include "hexlod/render/gl_api.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <thread>
#include <tuple>

namespace hexlod::lod {
namespace {

using grammar::TerminalSet;

// A terminal set of `count` random terminals of `shapes` shapes, sorted by shape; `coherent`
// sorts each shape's terminals along x too, so that an arena page holds neighbours, as a real
// set's pages hold a building's windows (and the pass can skip pages outside the frustum).
TerminalSet randomSet(std::mt19937& random, uint32_t count, uint32_t shapes, float extent,
                      bool coherent = false) {
    std::uniform_real_distribution<float> position(-extent, extent), unit(-1.0f, 1.0f), size(0.05f, 6.0f),
        ratio(0.0f, 2.0f);
    std::uniform_int_distribution<uint32_t> shape(0, shapes - 1);
    std::vector<grammar::TerminalRecord> records;
    for (uint32_t i = 0; i < count; ++i) {
        glm::quat q = glm::normalize(glm::quat(unit(random), unit(random), unit(random), unit(random)));
        glm::mat3 axes = glm::mat3_cast(q);
        records.push_back(grammar::packTerminal(
            glm::vec3(position(random), position(random), position(random) * 0.2f), axes[0], axes[1], axes[2],
            glm::vec2(size(random), size(random)), ratio(random), uint16_t(shape(random)), i));
    }
    std::stable_sort(records.begin(), records.end(), [&](const auto& a, const auto& b) {
        return std::tuple(a.shapeAndDepth & 0xffff, coherent ? a.position[0] : 0.0f) <
               std::tuple(b.shapeAndDepth & 0xffff, coherent ? b.position[0] : 0.0f);
    });
    TerminalSet set;
    set.countPerShape.assign(shapes, 0);
    for (const auto& r : records) ++set.countPerShape[r.shapeAndDepth & 0xffff];
    set.records.assign(records.begin(), records.end());
    return set;
}

class CullTest : public render::GlTest {};

// A tile grid of farthest depths as the cull pass reads it (DepthTiles' format).
struct OcclusionTexture {
    uint32_t id = 0, columns, rows;
    OcclusionTexture(uint32_t c, uint32_t r) : columns(c), rows(r) {
        gl::glCreateTextures(GL_TEXTURE_2D, 1, &id);
        gl::glTextureStorage2D(id, 1, GL_R32F, GLsizei(columns), GLsizei(rows));
    }
    ~OcclusionTexture() { gl::glDeleteTextures(1, &id); }
    void upload(const std::vector<float>& tiles) const {
        gl::glTextureSubImage2D(id, 0, 0, 0, GLsizei(columns), GLsizei(rows), GL_RED, GL_FLOAT, tiles.data());
    }
};

TEST_F(CullTest, TheGpuPassAgreesExactlyWithTheCpuReference) {
    GpuCull cull;
    std::string error;
    ASSERT_TRUE(cull.init(error)) << error;
    TerminalArena arena;
    ASSERT_TRUE(arena.create(1 << 18, error)) << error;
    std::mt19937 random(2024);
    const uint32_t shapesPerGrammar = 7;
    std::vector<TerminalSet> sets;
    for (int b = 0; b < 12; ++b)
        sets.push_back(randomSet(random, 1000 + 937 * b, shapesPerGrammar, 150.0f, b % 3 != 0));
    uint64_t skipped = 0, occludedPages = 0, fine = 0, coarse = 0, coarseWithImpostor = 0, listsSaved = 0,
             lod3Entries = 0, lod3ListsSaved = 0;
    for (int trial = 0; trial < 6; ++trial) {
        arena.beginFrame(trial);
        CullInputs inputs;
        // Two coarse shapes after the grammars' (CoarseMesh): one serves shape 3, which has no
        // impostor; the other serves shape 8, which has one, so only its LOD4 terminals may
        // draw it.
        const uint32_t coarse3 = 2 * shapesPerGrammar, coarse8 = coarse3 + 1;
        inputs.shapeCount = 2 * shapesPerGrammar + 2;
        inputs.shapeImpostor.assign(inputs.shapeCount, 1);
        inputs.shapeImpostor[3] = 0; // a shape without impostor stays LOD4
        inputs.shapeImpostor[coarse3] = inputs.shapeImpostor[coarse8] = 0;
        inputs.shapeCoarse.assign(inputs.shapeCount, glm::vec4(0.0f, 0.0f, 0.0f, -1.0f));
        inputs.shapeCoarse[3] = glm::vec4(0.02f, 0.01f, 0.3f, float(coarse3));
        inputs.shapeCoarse[8] = glm::vec4(0.002f, 0.004f, 0.01f, float(coarse8));
        // A city far from the world origin: the camera and cell origins are large doubles.
        const glm::dvec3 cityOrigin(1e7 * (trial % 2), -3e6 * (trial % 3), 50.0);
        std::uniform_real_distribution<double> offset(-200.0, 200.0), angle(0.0, 6.283);
        inputs.camera = cityOrigin + glm::dvec3(offset(random), offset(random), 1.7 + 40.0 * (trial % 3));
        for (size_t b = 0; b < sets.size(); ++b) {
            const ArenaBatch* resident = arena.acquire(b, sets[b]);
            ASSERT_TRUE(resident);
            inputs.batches.push_back({&sets[b], &resident->pages,
                                      cityOrigin + glm::dvec3(250.0 * (b % 4), 250.0 * (b / 4), 0.0),
                                      uint32_t(b % 2) * shapesPerGrammar, &resident->bounds});
        }
        // Roughly toward the middle of the batches, so every trial sees some and misses some.
        const glm::dvec3 middle = cityOrigin + glm::dvec3(375.0, 250.0, 0.0) - inputs.camera;
        const double a = std::atan2(middle.y, middle.x) + 0.15 * (angle(random) - 3.14);
        cells::Frustum frustum(inputs.camera, glm::dvec3(std::cos(a), std::sin(a), -0.1), glm::dvec3(0, 0, 1),
                               0.3 + 0.4 * trial, 16.0 / 9.0, 0.5, 800.0);
        scene::LodProfile profile;
        profile.maxScreenSpaceError = 1.0 + trial;
        inputs.frame = makeCullFrame(frustum, profile, 0.3 + 0.4 * trial, 720, 0.2, true);
        // The reference's frames (the last trial) draw every mesh in full. The first trial's
        // narrow view puts LOD3's distance far enough for a shape with an impostor to draw
        // its coarse mesh.
        if (trial != 5) setCoarseMeshes(inputs.frame, profile, 0.3 + 0.4 * trial, 720);
        // Odd trials test occlusion too, against a wall over the screen's left half at 40 to
        // 160 m (each tile's farthest depth) and open sky on the right.
        const uint32_t columns = 80, rows = 45;
        std::vector<float> tiles(columns * rows, 0.0f);
        OcclusionTexture texture(columns, rows);
        if (trial % 2) {
            setOcclusion(inputs.frame, glm::dvec3(std::cos(a), std::sin(a), -0.1), glm::dvec3(0, 0, 1),
                         0.3 + 0.4 * trial, 0.5, 800.0, 1280, 720, columns, rows, 16);
            std::uniform_real_distribution<float> wall(40.0f, 160.0f);
            for (uint32_t y = 0; y < rows; ++y)
                for (uint32_t x = 0; x < columns / 2; ++x)
                    tiles[y * columns + x] = inputs.frame.depthMap.x / wall(random) - inputs.frame.depthMap.y;
            texture.upload(tiles);
            inputs.occlusionTexture = texture.id;
            inputs.occlusionTiles = &tiles;
        }

        CullResult reference = cullOnCpu(inputs);
        std::vector<MeshDrawInfo> meshes(inputs.shapeCount, MeshDrawInfo{36, 0, 0});
        cull.run(inputs, arena.buffer(), meshes);
        std::vector<glm::uvec4> counters = cull.readCounters();
        std::vector<gpu::GpuTerminal> lists = cull.readLists(), lod3Lists = cull.readLod3Lists();
        const DrawListLayout& layout = cull.layout();
        uint64_t visible = 0;
        for (uint32_t s = 0; s < inputs.shapeCount; ++s) {
            uint32_t lod3 = 0;
            for (const CulledTerminal& e : reference.impostor[s]) lod3 += e.lod == HEXLOD_LOD3;
            ASSERT_EQ(counters[s].x, reference.lod4[s].size()) << "shape " << s << " trial " << trial;
            ASSERT_EQ(counters[s].y, 0u);
            ASSERT_EQ(counters[s].z, lod3) << "shape " << s << " trial " << trial;
            ASSERT_EQ(counters[s].w, reference.impostor[s].size() - lod3)
                << "shape " << s << " trial " << trial;
            // Each kind within its lists' capacity: LOD4 and LOD2 entries share theirs.
            ASSERT_LE(counters[s].z, layout.lod3Capacity[s]) << "shape " << s << " trial " << trial;
            if (s != coarse3) {
                ASSERT_LE(counters[s].x + counters[s].w, layout.capacity[s]);
            }
            // The coarse shape of a shape without impostor fills the lists it shares from the back.
            const uint32_t lod4First =
                s == coarse3 ? layout.base[s] + layout.capacity[s] - counters[s].x : layout.base[s];
            EXPECT_EQ(sortedIds(lists, lod4First, counters[s].x), sortedIds(reference.lod4[s], 0))
                << "shape " << s;
            EXPECT_EQ(sortedIds(lists, layout.base[s] + layout.capacity[s] - counters[s].w, counters[s].w),
                      sortedIds(reference.impostor[s], HEXLOD_LOD2))
                << "shape " << s;
            EXPECT_EQ(sortedIds(lod3Lists, layout.lod3Base[s], counters[s].z),
                      sortedIds(reference.impostor[s], HEXLOD_LOD3))
                << "shape " << s;
            visible += counters[s].x + counters[s].z + counters[s].w;
            // Only shapes with an impostor have LOD3 lists.
            if (!inputs.shapeImpostor[s]) {
                EXPECT_EQ(counters[s].z + counters[s].w, 0u);
                EXPECT_EQ(layout.lod3Capacity[s], 0u);
            }
        }
        EXPECT_EQ(layout.lod3Total, layout.lod3Base.back() + layout.lod3Capacity.back());
        EXPECT_LE(layout.lod3Total, layout.total);
        // The coarse shape of a shape without impostor shares the lists of the shape it serves
        // and adds nothing to them; that of a shape with one has lists of its own, as long as
        // shape 8's terminals in the pages within LOD4's distance. Only LOD4 entries go there.
        EXPECT_EQ(layout.base[coarse3], layout.base[3]);
        EXPECT_EQ(layout.capacity[coarse3], layout.capacity[3]);
        EXPECT_LE(layout.capacity[coarse8], layout.capacity[8]);
        EXPECT_EQ(layout.base[coarse8], layout.base[coarse3 - 1] + layout.capacity[coarse3 - 1]);
        EXPECT_EQ(layout.total, layout.base[coarse8] + layout.capacity[coarse8]);
        EXPECT_LE(counters[3].x + counters[coarse3].x, layout.capacity[3]);
        EXPECT_LE(counters[coarse8].x, layout.capacity[coarse8]);
        EXPECT_EQ(counters[coarse3].z + counters[coarse3].w + counters[coarse8].z + counters[coarse8].w, 0u);
        if (trial == 5) {
            EXPECT_EQ(counters[coarse3].x + counters[coarse8].x, 0u);
        }
        // Draw lists that may not hold the coarse shapes' own lists leave them out: shape 8
        // then draws its full mesh, in both passes.
        if (trial == 0) {
            ASSERT_GT(counters[coarse8].x, 0u);
            CullInputs tight = inputs;
            tight.maxListRecords = layout.total - 1;
            const CullResult tightReference = cullOnCpu(tight);
            cull.run(tight, arena.buffer(), meshes);
            const std::vector<glm::uvec4> tightCounters = cull.readCounters();
            EXPECT_LE(cull.layout().total, tight.maxListRecords);
            EXPECT_EQ(cull.layout().capacity[coarse8], 0u);
            EXPECT_EQ(tightCounters[coarse8].x + tightReference.lod4[coarse8].size(), 0u);
            EXPECT_EQ(tightCounters[8].x, counters[8].x + counters[coarse8].x);
            EXPECT_EQ(tightReference.lod4[8].size(), tightCounters[8].x);
            EXPECT_EQ(tightCounters[coarse3].x, counters[coarse3].x)
                << "a shape without impostor keeps its coarse mesh";
        }
        fine += counters[3].x;
        coarse += counters[coarse3].x;
        coarseWithImpostor += counters[coarse8].x;
        listsSaved += layout.capacity[8] - layout.capacity[coarse8];
        for (uint32_t s = 0; s < inputs.shapeCount; ++s) {
            lod3Entries += counters[s].z;
            if (inputs.shapeImpostor[s]) lod3ListsSaved += layout.capacity[s] - layout.lod3Capacity[s];
        }
        // Some of everything: the trial would prove little if all were culled or all LOD4.
        EXPECT_GT(visible, 0u);
        EXPECT_GT(reference.culled, 0u);
        const GpuCull::PageStats pages = cull.pageStats();
        EXPECT_LE(pages.skippedTerminals, reference.culled); // a skipped page holds no visible terminal
        if (trial % 2) {
            EXPECT_GT(reference.occluded, 0u) << "trial " << trial;
            occludedPages += pages.occludedTerminals;
            // A hidden page's terminals count as occluded, though the frustum or backface test
            // would cull some of them first; with no page skipped, the pass hides exactly the
            // reference's terminals.
            CullInputs everyPage = inputs;
            for (CullBatchInput& batch : everyPage.batches) batch.pageBounds = nullptr;
            cull.run(everyPage, arena.buffer(), meshes);
            EXPECT_EQ(cull.readOccluded(), reference.occluded) << "trial " << trial;
        }
        skipped += pages.skippedTerminals;
    }
    // Pages were skipped whole, outside the frustum and behind the wall, and the lists above
    // still match the reference, which skips none.
    EXPECT_GT(skipped, 0u);
    EXPECT_GT(occludedPages, 0u);
    // Near terminals kept their shape's mesh and far ones took the coarse one, with or without
    // an impostor; pages beyond LOD4's distance reserved no room for coarse entries.
    EXPECT_GT(fine, 0u);
    EXPECT_GT(coarse, 0u);
    EXPECT_GT(coarseWithImpostor, 0u);
    EXPECT_GT(listsSaved, 0u);
    // LOD3 entries went to lists of their own, which pages beyond LOD2's distance left smaller.
    EXPECT_GT(lod3Entries, 0u);
    EXPECT_GT(lod3ListsSaved, 0u);
}

// Hand-placed terminals: a 2 m x 2 m facade tile facing -y at the origin of its cell.
struct Placed {
    gpu::GpuTerminal record;
    TerminalSet set;
};

Placed facadeTile(glm::vec3 corner, float depthRatio) {
    Placed placed;
    grammar::TerminalRecord r = grammar::packTerminal(corner, glm::vec3(1, 0, 0), glm::vec3(0, 0, 1),
                                                      glm::vec3(0, -1, 0), glm::vec2(2.0f), depthRatio, 0, 0);
    std::memcpy(&placed.record, &r, sizeof r);
    placed.set.countPerShape = {1};
    placed.set.records.push_back(r);
    return placed;
}

uint32_t classify(const Placed& placed, const glm::dvec3& camera, const glm::dvec3& forward, double maxSse) {
    CullInputs inputs;
    inputs.shapeCount = 1;
    inputs.shapeImpostor = {1};
    inputs.camera = camera;
    inputs.batches.push_back({&placed.set, nullptr, glm::dvec3(0.0), 0});
    cells::Frustum frustum(camera, forward, glm::dvec3(0, 0, 1), 1.0, 1.5, 0.1, 5000.0);
    scene::LodProfile profile;
    profile.maxScreenSpaceError = maxSse;
    inputs.frame = makeCullFrame(frustum, profile, 1.0, 720, 0.2, true);
    CullResult result = cullOnCpu(inputs);
    if (!result.lod4[0].empty()) return HEXLOD_LOD4;
    if (!result.impostor[0].empty()) return result.impostor[0][0].lod;
    return HEXLOD_CULLED;
}

TEST(CullRulesTest, FrustumBackfaceAndDistanceDecideAsDocumented) {
    Placed tile = facadeTile(glm::vec3(0.0f), 0.25f); // 0.5 m deep
    const glm::dvec3 north(0, 1, 0);
    // In front (the tile faces -y), looking at it: LOD4 close, impostors further away.
    EXPECT_EQ(classify(tile, {1, -5, 1}, north, 2.0), HEXLOD_LOD4);
    EXPECT_EQ(classify(tile, {1, -200, 1}, north, 2.0), HEXLOD_LOD3);
    EXPECT_EQ(classify(tile, {1, -3000, 1}, north, 2.0), HEXLOD_LOD2);
    // Looking away: outside the frustum.
    EXPECT_EQ(classify(tile, {1, -5, 1}, -north, 2.0), HEXLOD_CULLED);
    // Behind the wall, further than the tile's depth: backface culled.
    EXPECT_EQ(classify(tile, {1, 2, 1}, -north, 2.0), HEXLOD_CULLED);
    // Just behind the wall plane but within its protrusion: still visible.
    EXPECT_EQ(classify(tile, {1, 0.3, 1}, glm::dvec3(0, -1, -0.2), 2.0), HEXLOD_LOD4);
    // A larger error budget moves every switch closer.
    EXPECT_EQ(classify(tile, {1, -200, 1}, north, 16.0), HEXLOD_LOD2);
}

TEST(CullRulesTest, ACoarseMeshServesFromWhereItsDeviationProjectsUnderTheBound) {
    const Placed tile = facadeTile(glm::vec3(0.0f), 0.25f); // 2 m x 2 m, 0.5 m deep
    const glm::vec3 deviation(0.01f, 0.01f, 0.1f);          // 2 cm, 2 cm and 5 cm on this tile
    scene::LodProfile profile;
    profile.maxScreenSpaceError = 2.0;
    // Which shape the tile draws with at LOD4 from `distance` in front of its centre: 0, its own
    // mesh; 1, the coarse one; -1, none (an impostor, or culled).
    const auto drawnShape = [&](double distance, bool coarseMeshes, uint8_t impostor = 0) {
        CullInputs inputs;
        inputs.shapeCount = 2;
        inputs.shapeImpostor = {impostor, 0}; // no impostor: LOD4 at any distance
        inputs.shapeCoarse = {glm::vec4(deviation, 1.0f), glm::vec4(0.0f, 0.0f, 0.0f, -1.0f)};
        inputs.camera = glm::dvec3(1.0, -distance, 1.0);
        inputs.batches.push_back({&tile.set, nullptr, glm::dvec3(0.0), 0});
        cells::Frustum frustum(inputs.camera, glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1), 1.0, 1.5, 0.1,
                               5000.0);
        inputs.frame = makeCullFrame(frustum, profile, 1.0, 720, 0.2, true);
        if (coarseMeshes) setCoarseMeshes(inputs.frame, profile, 1.0, 720);
        const CullResult result = cullOnCpu(inputs);
        return !result.lod4[1].empty() ? 1 : !result.lod4[0].empty() ? 0 : -1;
    };
    const double reach =
        glm::length(deviation * glm::vec3(2.0f, 2.0f, 0.5f)) * lodDistance(1.0, profile, 1.0, 720);
    EXPECT_NEAR(reach, 18.9, 0.1);
    EXPECT_EQ(drawnShape(0.95 * reach, true), 0);
    EXPECT_EQ(drawnShape(1.05 * reach, true), 1);
    EXPECT_EQ(drawnShape(100.0 * reach, true), 1);
    // Without coarse meshes in the frame (the all-LOD4 reference) the tile keeps its mesh.
    EXPECT_EQ(drawnShape(1.05 * reach, false), 0);
    // With an impostor, the coarse mesh serves from the same distance to LOD3's, and the
    // impostor beyond.
    const double lod3 = lodDistance(profile.geometricError[3], profile, 1.0, 720);
    ASSERT_GT(lod3, 2.0 * reach);
    EXPECT_EQ(drawnShape(0.95 * reach, true, 1), 0);
    EXPECT_EQ(drawnShape(1.05 * reach, true, 1), 1);
    EXPECT_EQ(drawnShape(0.95 * lod3, true, 1), 1);
    EXPECT_EQ(drawnShape(1.05 * lod3, true, 1), -1);
}

TEST(CullRulesTest, APageHoldsNoLod4EntryOnlyWhenWhollyBeyondLod3sDistance) {
    shared::CullFrame frame{};
    frame.lodDistance = glm::vec4(100.0f * 100.0f, 400.0f * 400.0f, 0.15f, 1.0f);
    const glm::vec3 origin(0.0f, 1000.0f, 0.0f); // the batch's cell origin minus the camera
    // A sphere of radius 10 centred 105 m away reaches to 95 m; centred 111 m away, to 101 m.
    EXPECT_TRUE(pageMayHoldLod4(glm::vec4(0.0f, -895.0f, 0.0f, 10.0f), origin, frame));
    EXPECT_FALSE(pageMayHoldLod4(glm::vec4(0.0f, -889.0f, 0.0f, 10.0f), origin, frame));
    // The camera inside the sphere, an unbounded page, and a frame without LOD distances.
    EXPECT_TRUE(pageMayHoldLod4(glm::vec4(0.0f, -1000.0f, 0.0f, 5.0f), origin, frame));
    EXPECT_TRUE(pageMayHoldLod4(glm::vec4(0.0f, 0.0f, 0.0f, INFINITY), origin, frame));
    frame.lodDistance.w = 0.0f;
    EXPECT_TRUE(pageMayHoldLod4(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), origin, frame));
}

TEST_F(CullTest, ArenaEvictsTheLeastRecentlyDrawnWhenFull) {
    TerminalArena arena;
    std::string error;
    ASSERT_TRUE(arena.create(3000, error)) << error; // 47 pages of 64: 3008 records
    std::mt19937 random(1);
    TerminalSet a = randomSet(random, 1000, 2, 10), b = randomSet(random, 1000, 2, 10),
                c = randomSet(random, 1500, 2, 10);
    arena.beginFrame(1);
    ASSERT_TRUE(arena.acquire(1, a));
    arena.beginFrame(2);
    ASSERT_TRUE(arena.acquire(2, b));
    arena.beginFrame(3);
    ASSERT_TRUE(arena.acquire(2, b)); // b drawn again: a is now the oldest
    ASSERT_TRUE(arena.acquire(3, c)); // needs 24 pages, 15 are free: evicts a only, though not adjacent
    EXPECT_FALSE(arena.resident(1));
    EXPECT_TRUE(arena.resident(2));
    EXPECT_TRUE(arena.resident(3));
    EXPECT_EQ(arena.stats().evictions, 1u);
    EXPECT_EQ(arena.stats().residentRecords, 2500u);
    EXPECT_EQ(arena.stats().freePages, 47u - 16u - 24u);
    // The page tables of the 16 + 24 resident pages, counted with the arena's bytes.
    EXPECT_EQ(arena.stats().pageTableBytes, (16u + 24u) * (sizeof(uint32_t) + sizeof(PageBounds)));
    // Everything resident is in use this frame: a set that does not fit is refused, not forced.
    TerminalSet d = randomSet(random, 1000, 2, 10);
    EXPECT_FALSE(arena.acquire(4, d));
    EXPECT_EQ(arena.stats().rejected, 1u);
    TerminalSet huge = randomSet(random, 4000, 2, 10);
    EXPECT_FALSE(arena.acquire(5, huge));
    EXPECT_FALSE(arena.create(0, error));
}

// Page bounds are compared field by field: the struct has padding.
void expectSameBounds(const std::vector<PageBounds>& got, const std::vector<PageBounds>& expected) {
    ASSERT_EQ(got.size(), expected.size());
    for (size_t p = 0; p < got.size(); ++p) {
        EXPECT_EQ(got[p].sphere, expected[p].sphere) << p;
        EXPECT_EQ(got[p].boxMin, expected[p].boxMin) << p;
        EXPECT_EQ(got[p].boxMax, expected[p].boxMax) << p;
        EXPECT_EQ(got[p].faceCount, expected[p].faceCount) << p;
        for (uint32_t f = 0; f < got[p].faceCount; ++f) EXPECT_EQ(got[p].faces[f], expected[p].faces[f]) << p;
        EXPECT_EQ(got[p].firstBuilding, expected[p].firstBuilding) << p;
        EXPECT_EQ(got[p].lastBuilding, expected[p].lastBuilding) << p;
    }
}

// Bounds prepared on another thread are the ones the frame would compute, handed over once;
// they go when their set does (bounds that do not fit a set: ArenaTakesPageBoundsPrepared...).
TEST(PreparedPageBoundsTest, HandsOverEachSetsBoundsOnceWhileTheSetLives) {
    std::mt19937 random(4);
    auto a = std::make_shared<const TerminalSet>(randomSet(random, 1000, 2, 50, true));
    auto b = std::make_shared<const TerminalSet>(randomSet(random, 130, 2, 50, true));
    PreparedPageBounds prepared;
    std::thread([&] {
        prepared.prepare(1, a);
        prepared.prepare(2, b);
        prepared.prepare(3, nullptr); // nothing to prepare
    }).join();
    EXPECT_EQ(prepared.size(), 2u);
    EXPECT_EQ(prepared.byteSize(), (16u + 3u) * sizeof(PageBounds));
    EXPECT_TRUE(prepared.take(9).empty()); // never prepared
    expectSameBounds(prepared.take(1), pageBounds(*a));
    EXPECT_TRUE(prepared.take(1).empty()); // handed over already
    expectSameBounds(prepared.take(2), pageBounds(*b));
    EXPECT_EQ(prepared.size(), 0u);
    // A set the cache lets go of takes its bounds along.
    prepared.prepare(2, b);
    b.reset();
    EXPECT_TRUE(prepared.take(1).empty());
    EXPECT_EQ(prepared.size(), 0u);
    EXPECT_EQ(prepared.byteSize(), 0u);
}

TEST(PreparedPageBoundsTest, ThreadsPrepareAndTakeAtOnce) {
    std::mt19937 random(5);
    std::vector<std::shared_ptr<const TerminalSet>> sets;
    for (int i = 0; i < 32; ++i)
        sets.push_back(std::make_shared<const TerminalSet>(randomSet(random, 200 + 37 * i, 2, 50, true)));
    PreparedPageBounds prepared;
    std::vector<std::thread> threads;
    for (size_t t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            for (size_t i = t; i < sets.size(); i += 4) prepared.prepare(i, sets[i]);
        });
    size_t taken = 0;
    for (int round = 0; round < 4; ++round)
        for (size_t i = 0; i < sets.size(); ++i) {
            const std::vector<PageBounds> bounds = prepared.take(i);
            if (bounds.empty()) continue;
            expectSameBounds(bounds, pageBounds(*sets[i]));
            ++taken;
        }
    for (std::thread& t : threads) t.join();
    for (size_t i = 0; i < sets.size(); ++i)
        if (!prepared.take(i).empty()) ++taken;
    EXPECT_EQ(taken, sets.size()); // each set's bounds handed over exactly once
}

// The arena uploads a set with prepared bounds as they are, and computes its own where the
// prepared ones do not fit the set.
TEST_F(CullTest, ArenaTakesPageBoundsPreparedOffTheFrame) {
    TerminalArena arena;
    std::string error;
    ASSERT_TRUE(arena.create(4096, error)) << error;
    std::mt19937 random(6);
    const TerminalSet a = randomSet(random, 1000, 2, 50, true), b = randomSet(random, 700, 2, 50, true);
    arena.beginFrame(1);
    std::vector<PageBounds> forA = pageBounds(a);
    forA[3].firstBuilding = 123456; // marks them as the prepared ones
    const ArenaBatch* first = arena.acquire(1, a, forA);
    ASSERT_NE(first, nullptr);
    EXPECT_EQ(first->bounds[3].firstBuilding, 123456u);
    const ArenaBatch* second = arena.acquire(2, b, pageBounds(a)); // 16 pages for a set of 11
    ASSERT_NE(second, nullptr);
    expectSameBounds(second->bounds, pageBounds(b));
    EXPECT_EQ(arena.stats().uploads, 2u);
    EXPECT_EQ(arena.stats().preparedUploads, 1u);
    arena.beginFrame(2);
    EXPECT_EQ(arena.acquire(1, a)->bounds[3].firstBuilding, 123456u); // resident: kept as uploaded
    EXPECT_EQ(arena.stats().preparedUploads, 0u);
}

// The cull pass binds the arena as one storage block: asked for more than the GL's largest,
// the arena holds what that block does (llvmpipe: 128 MiB, 4 M records), not a buffer whose
// records past the block a shader would never read.
TEST_F(CullTest, ArenaStaysWithinTheGlsLargestStorageBlock) {
    GLint64 maxBlockBytes = 0;
    gl::glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlockBytes);
    ASSERT_GT(maxBlockBytes, 0);
    const uint64_t blockRecords = uint64_t(maxBlockBytes) / sizeof(grammar::TerminalRecord);
    TerminalArena arena;
    std::string error;
    ASSERT_TRUE(arena.create(blockRecords + 10 * kArenaPageRecords, error)) << error;
    EXPECT_EQ(arena.stats().capacityRecords, blockRecords / kArenaPageRecords * kArenaPageRecords);
    EXPECT_EQ(arena.stats().requestedRecords, blockRecords + 10 * kArenaPageRecords);
    EXPECT_LE(arena.byteSize(), uint64_t(maxBlockBytes));
}

} // namespace
} // namespace hexlod::lod
