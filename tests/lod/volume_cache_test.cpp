// The base volume cache's budget: least recently drawn meshes go first, but never one the last
// frame drew, so a view that needs more than the budget does not rebuild the same meshes
// frame after frame; LOD1's elements are built only for batches a frame draws at LOD1.
#include "../render/gl_fixture.h"
#include "test_city.h"

#include "hexlod/lod/volume_cache.h"

namespace hexlod::lod {
namespace {

class VolumeCacheTest : public render::GlTest {};

TEST_F(VolumeCacheTest, OverBudgetOnlyMeshesTheLastFrameDidNotDrawAreRebuilt) {
    testing::TestCity city = testing::makeCity(40, 0);
    ASSERT_GE(city.catalog->batchCount(), 3u);
    VolumeCache volumes(*city.catalog, 1); // every mesh is over budget
    const auto drawFrame = [&](uint64_t frame, std::initializer_list<uint32_t> batches) {
        volumes.beginFrame(frame);
        for (uint32_t b : batches) EXPECT_GT(volumes.acquire(b, 0.0f).indexCount, 0u) << "batch " << b;
        return volumes.stats().built;
    };
    EXPECT_EQ(drawFrame(1, {0, 1}), 2u);
    EXPECT_EQ(drawFrame(2, {0, 1, 2}), 1u); // 0 and 1 stay: frame 1 drew them
    EXPECT_EQ(drawFrame(3, {2}), 0u);
    EXPECT_EQ(volumes.stats().resident, 3u); // frame 2 drew all three
    EXPECT_EQ(drawFrame(4, {0, 2}), 1u);     // 0 and 1, unused since frame 2, went: 0 is built again
    EXPECT_EQ(volumes.stats().resident, 2u);
}

TEST_F(VolumeCacheTest, Lod1sElementsAreBuiltOnlyWhenAFrameDrawsTheBatchAtLod1) {
    testing::TestCity city = testing::makeCity(40, 0);
    VolumeCache volumes(*city.catalog, uint64_t(1) << 30);
    volumes.beginFrame(1);
    const VolumeMesh& lod0 = volumes.acquire(0, 0.0f);
    EXPECT_EQ(lod0.elementBuffer, 0u);
    EXPECT_EQ(lod0.parameterBuffer, 0u);
    const uint64_t walls = volumes.stats().residentBytes;
    EXPECT_EQ(walls, lod0.bytes);
    // The same mesh, now drawn at LOD1: its elements join it, counted in its bytes.
    const VolumeMesh& lod1 = volumes.acquire(0, 0.0f, true);
    EXPECT_EQ(&lod1, &lod0);
    EXPECT_NE(lod1.elementBuffer, 0u);
    EXPECT_NE(lod1.parameterBuffer, 0u);
    EXPECT_GT(volumes.stats().residentBytes, walls);
    EXPECT_EQ(volumes.stats().residentBytes, lod1.bytes);
    EXPECT_EQ(volumes.stats().built, 1u); // one mesh, not rebuilt
    const uint32_t elements = lod1.elementBuffer;
    EXPECT_EQ(volumes.acquire(0, 0.0f, true).elementBuffer, elements);
    EXPECT_EQ(volumes.acquire(0, 0.0f).elementBuffer, elements); // kept for LOD0's draws too
    // Shells under terminal sets (inset above 0) never carry them; a mesh built for LOD1 has
    // them from the start.
    EXPECT_EQ(volumes.acquire(1, 0.5f, true).elementBuffer, 0u);
    EXPECT_NE(volumes.acquire(2, 0.0f, true).elementBuffer, 0u);
    EXPECT_EQ(volumes.stats().built, 3u);
}

} // namespace
} // namespace hexlod::lod
