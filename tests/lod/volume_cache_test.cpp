// The base volume cache's budget: least recently drawn meshes go first, but never one the last
// frame drew, so a view that needs more than the budget does not rebuild the same meshes
// frame after frame.
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

} // namespace
} // namespace hexlod::lod
