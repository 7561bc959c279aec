// A species' view averages (the point form of far trees): alpha-weighted mean albedo and
// normal over each view's own tile, and the share of the tile the tree covers.
#include "hexlod/lod/tree_view_averages.h"

#include <gtest/gtest.h>

namespace hexlod::lod {
namespace {

TEST(TreeViewAverages, EachViewAveragesItsOwnTileWeightedByCoverage) {
    impostor::ImpostorAtlas atlas;
    atlas.layout = {impostor::ViewSphere::FullSphere, 2, 8, 2}; // 4 views of 4 x 4 inner texels
    const uint32_t size = atlas.layout.atlasSize();
    atlas.albedo = render::Image(size, size, 4);
    atlas.normalDepth = render::Image(size, size, 4);
    // View 1: a quarter of its inner texels red, facing +x, half covered; view 3: one green
    // texel facing +z, fully covered; views 0 and 2 empty.
    const glm::uvec2 one = atlas.layout.tileOrigin(1) + glm::uvec2(2),
                     three = atlas.layout.tileOrigin(3) + glm::uvec2(2);
    for (uint32_t y = 0; y < 2; ++y)
        for (uint32_t x = 0; x < 2; ++x) {
            float* a = atlas.albedo.at(one.x + x, one.y + y);
            a[0] = 1.0f, a[3] = 0.5f;
            atlas.normalDepth.at(one.x + x, one.y + y)[0] = 1.0f;
        }
    atlas.albedo.at(three.x, three.y)[1] = 1.0f;
    atlas.albedo.at(three.x, three.y)[3] = 1.0f;
    atlas.normalDepth.at(three.x, three.y)[2] = 1.0f;
    // A texel in view 1's padding is outside every view's inner square: never counted.
    atlas.albedo.at(atlas.layout.tileOrigin(1).x, atlas.layout.tileOrigin(1).y)[3] = 1.0f;

    const std::vector<glm::vec4> averages = treeViewAverages(atlas);
    ASSERT_EQ(averages.size(), 8u);
    EXPECT_EQ(averages[0], glm::vec4(0.0f));
    EXPECT_EQ(averages[2], glm::vec4(1.0f, 0.0f, 0.0f, 4 * 0.5f / 16.0f));
    EXPECT_EQ(averages[3], glm::vec4(1.0f, 0.0f, 0.0f, 0.0f));
    EXPECT_EQ(averages[4], glm::vec4(0.0f));
    EXPECT_EQ(averages[6], glm::vec4(0.0f, 1.0f, 0.0f, 1.0f / 16.0f));
    EXPECT_EQ(averages[7], glm::vec4(0.0f, 0.0f, 1.0f, 0.0f));
}

} // namespace
} // namespace hexlod::lod
