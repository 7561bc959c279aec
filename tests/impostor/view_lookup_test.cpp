// View grids and the nearest-view lookup: directions, grid positions, and the weight
// properties LOD3 relies on (sum 1, exact views, continuity, grazing and rim directions, NaN).
#include "hexlod/impostor/view_lookup.h"

#include <gtest/gtest.h>

#include <array>

#include <cmath>
#include <limits>
#include <map>
#include <random>

namespace hexlod::impostor {
namespace {

ViewLayout layout(ViewSphere sphere, uint32_t grid) {
    ViewLayout l;
    l.sphere = sphere;
    l.grid = grid;
    return l;
}

// The grid position (column, row) a view direction maps back to: integers are views.
glm::vec2 gridPositionOf(const ViewLayout& l, const glm::vec3& d) {
    if (l.sphere == ViewSphere::Hemisphere)
        return (encodeHemiOctahedral(d) + 1.0f) * (0.5f * float(l.grid - 1));
    return (encodeOctahedral(d) + 1.0f) * (0.5f * float(l.grid)) - 0.5f;
}

float weightSum(const ViewWeights& w) {
    return w.weights[0] + w.weights[1] + w.weights[2] + w.weights[3];
}

// The blend as a map view -> weight, so two blends can be compared whatever their order.
std::map<uint32_t, float> asMap(const ViewWeights& w) {
    std::map<uint32_t, float> m;
    for (uint32_t i = 0; i < w.count; ++i) m[w.views[i]] += w.weights[i];
    return m;
}

float blendDistance(const ViewWeights& a, const ViewWeights& b) {
    std::map<uint32_t, float> ma = asMap(a), mb = asMap(b);
    float d = 0.0f;
    for (auto& [view, weight] : ma) d += std::abs(weight - (mb.count(view) ? mb[view] : 0.0f));
    for (auto& [view, weight] : mb)
        if (!ma.count(view)) d += weight;
    return d;
}

TEST(ViewLayoutTest, HemisphereGridReachesTheRimAndLooksStraightOnAtItsCentre) {
    ViewLayout l = layout(ViewSphere::Hemisphere, 9);
    glm::vec3 centre = l.direction(4 * 9 + 4);
    EXPECT_NEAR(centre.z, 1.0f, 1e-6f);
    // Corners and edges of the grid lie on the rim (z = 0): grazing views.
    for (uint32_t index : {0u, 8u, 72u, 80u, 4u, 36u})
        EXPECT_NEAR(l.direction(index).z, 0.0f, 1e-6f) << index;
    for (uint32_t v = 0; v < l.viewCount(); ++v) {
        glm::vec3 d = l.direction(v);
        EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
        EXPECT_GE(d.z, 0.0f);
        glm::vec2 g = gridPositionOf(l, d);
        EXPECT_NEAR(g.x, float(v % 9), 1e-4f);
        EXPECT_NEAR(g.y, float(v / 9), 1e-4f);
    }
}

TEST(ViewLayoutTest, FullSphereGridHasDistinctDirectionsEverywhere) {
    ViewLayout l = layout(ViewSphere::FullSphere, 8);
    int below = 0, above = 0;
    for (uint32_t v = 0; v < l.viewCount(); ++v) {
        glm::vec3 d = l.direction(v);
        if (d.z < -1e-6f) ++below;
        if (d.z > 1e-6f) ++above;
        for (uint32_t w = 0; w < v; ++w) EXPECT_GT(glm::length(d - l.direction(w)), 0.05f) << v << " " << w;
        glm::vec2 g = gridPositionOf(l, d);
        EXPECT_NEAR(g.x, float(v % 8), 1e-4f);
        EXPECT_NEAR(g.y, float(v / 8), 1e-4f);
    }
    // Symmetric about the equator: 24 views below, 24 above, 16 on it.
    EXPECT_EQ(below, 24);
    EXPECT_EQ(above, 24);
}

TEST(ViewLayoutTest, OctahedralMapsRoundTrip) {
    std::mt19937 random(3);
    std::normal_distribution<float> n;
    for (int i = 0; i < 1000; ++i) {
        glm::vec3 d = glm::normalize(glm::vec3(n(random), n(random), n(random)));
        glm::vec3 back = decodeOctahedral(encodeOctahedral(d));
        EXPECT_NEAR(glm::length(back - d), 0.0f, 1e-5f);
        glm::vec3 h = glm::vec3(d.x, d.y, std::abs(d.z));
        EXPECT_NEAR(glm::length(decodeHemiOctahedral(encodeHemiOctahedral(h)) - h), 0.0f, 1e-5f);
    }
}

TEST(ViewLayoutTest, ValidationNamesWhatIsWrong) {
    std::string error;
    EXPECT_TRUE(layout(ViewSphere::Hemisphere, 8).validate(error)) << error;
    EXPECT_FALSE(layout(ViewSphere::Hemisphere, 1).validate(error));
    EXPECT_EQ(error, "view grid 1 is outside [2, 32]");
    EXPECT_FALSE(layout(ViewSphere::Hemisphere, 33).validate(error));
    ViewLayout tight = layout(ViewSphere::Hemisphere, 8);
    tight.viewResolution = 4;
    tight.padding = 2;
    EXPECT_FALSE(tight.validate(error));
    EXPECT_NE(error.find("no inner area"), std::string::npos);
    ViewLayout huge = layout(ViewSphere::Hemisphere, 32);
    huge.viewResolution = 1024;
    EXPECT_FALSE(huge.validate(error));
    EXPECT_NE(error.find("exceeds 16384"), std::string::npos);
}

class ViewLookupTest : public ::testing::TestWithParam<std::tuple<ViewSphere, uint32_t>> {};

TEST_P(ViewLookupTest, WeightsSumToOneAndAnExactViewGetsAll) {
    auto [sphere, grid] = GetParam();
    ViewLookup lookup(layout(sphere, grid));
    for (uint32_t v = 0; v < lookup.layout().viewCount(); ++v) {
        ViewWeights w;
        ASSERT_TRUE(lookup.nearestViews(lookup.layout().direction(v), w));
        EXPECT_EQ(w.views[0], v);
        EXPECT_FLOAT_EQ(w.weights[0], 1.0f);
        EXPECT_FLOAT_EQ(weightSum(w), 1.0f);
    }
    std::mt19937 random(11);
    std::normal_distribution<float> n;
    std::array<int, 5> counts{};
    for (int i = 0; i < 2000; ++i) {
        glm::vec3 d(n(random), n(random), n(random));
        ViewWeights w;
        ASSERT_TRUE(lookup.nearestViews(d, w));
        EXPECT_NEAR(weightSum(w), 1.0f, 1e-5f);
        for (float weight : w.weights) {
            EXPECT_TRUE(std::isfinite(weight));
            EXPECT_GE(weight, 0.0f);
        }
        // Views whose share fell to the floor have dropped out: the rest come first, largest first.
        EXPECT_GE(w.count, 1u);
        EXPECT_LE(w.count, std::min<uint32_t>(4, grid * grid));
        for (uint32_t k = 0; k < 4; ++k) {
            EXPECT_EQ(w.weights[k] > 0.0f, k < w.count);
            if (k > 0) {
                EXPECT_LE(w.weights[k], w.weights[k - 1]);
            }
        }
        counts[w.count] += 1;
    }
    // Between the views, two or more blend.
    EXPECT_GT(counts[2] + counts[3] + counts[4], 0);
}

// The largest change of the blend between neighbouring samples of the arc from a to b.
float largestStep(const ViewLookup& lookup, const glm::vec3& a, const glm::vec3& b, int steps) {
    ViewWeights previous;
    EXPECT_TRUE(lookup.nearestViews(a, previous));
    float largest = 0.0f;
    for (int s = 1; s <= steps; ++s) {
        float t = float(s) / float(steps);
        ViewWeights w;
        EXPECT_TRUE(lookup.nearestViews(glm::normalize((1 - t) * a + t * b), w));
        largest = std::max(largest, blendDistance(previous, w));
        previous = w;
    }
    return largest;
}

TEST_P(ViewLookupTest, WeightsAreContinuousAlongPathsAcrossTheGrid) {
    auto [sphere, grid] = GetParam();
    ViewLookup lookup(layout(sphere, grid));
    // Along arcs that cross many changes of the nearest-view set, a jump would stay as large
    // when the sampling gets four times finer; a continuous blend shrinks with the step.
    std::mt19937 random(5);
    std::normal_distribution<float> n;
    for (int path = 0; path < 12; ++path) {
        glm::vec3 a = glm::normalize(glm::vec3(n(random), n(random), std::abs(n(random))));
        glm::vec3 b = glm::normalize(glm::vec3(n(random), n(random), std::abs(n(random))));
        float coarse = largestStep(lookup, a, b, 2000), fine = largestStep(lookup, a, b, 8000);
        EXPECT_LT(fine, 0.5f * coarse + 1e-4f) << "path " << path;
        // The share floor makes the blend up to 1 / (1 - 4 kMinViewShare) times steeper.
        EXPECT_LT(fine, 0.05f / (1.0f - 4.0f * kMinViewShare)) << "path " << path;
    }
}

INSTANTIATE_TEST_SUITE_P(Grids, ViewLookupTest,
                         ::testing::Values(std::make_tuple(ViewSphere::Hemisphere, 2u),
                                           std::make_tuple(ViewSphere::Hemisphere, 3u),
                                           std::make_tuple(ViewSphere::Hemisphere, 8u),
                                           std::make_tuple(ViewSphere::Hemisphere, 32u),
                                           std::make_tuple(ViewSphere::FullSphere, 8u)));

TEST(ViewLookupEdgeTest, GrazingRimAndBehindTheWallAreDefined) {
    ViewLookup lookup(layout(ViewSphere::Hemisphere, 8));
    for (glm::vec3 d : {glm::vec3(1, 0, 0), glm::vec3(0, -1, 1e-7f), glm::vec3(0.7f, 0.7f, -0.01f),
                        glm::vec3(0, 0, -1), glm::vec3(1e-30f, 0, 0)}) {
        ViewWeights w;
        ASSERT_TRUE(lookup.nearestViews(d, w)) << d.x << " " << d.y << " " << d.z;
        EXPECT_NEAR(weightSum(w), 1.0f, 1e-5f);
        for (uint32_t i = 0; i < w.count; ++i) EXPECT_GE(lookup.layout().direction(w.views[i]).z, 0.0f);
    }
    // Straight behind the wall falls back to the front view.
    ViewWeights behind;
    ASSERT_TRUE(lookup.nearestViews(glm::vec3(0, 0, -1), behind));
    EXPECT_NEAR(lookup.layout().direction(behind.views[0]).z, 1.0f, 0.2f);
}

TEST(ViewLookupEdgeTest, NanInfiniteAndZeroDirectionsAreRejected) {
    ViewLookup lookup(layout(ViewSphere::FullSphere, 8));
    float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    ViewWeights w;
    EXPECT_FALSE(lookup.nearestViews(glm::vec3(nan, 0, 1), w));
    EXPECT_FALSE(lookup.nearestViews(glm::vec3(0, inf, 1), w));
    EXPECT_FALSE(lookup.nearestViews(glm::vec3(0, 0, 0), w));
    EXPECT_EQ(w.count, 0u);
}

TEST(ViewLookupEdgeTest, TheDirectionTableMatchesTheLookupAtTexelCentres) {
    ViewLookup lookup(layout(ViewSphere::Hemisphere, 8));
    DirectionTable table = lookup.buildTable(32);
    ASSERT_EQ(table.texels.size(), 32u * 32u);
    for (uint32_t y = 0; y < 32; y += 5) {
        for (uint32_t x = 0; x < 32; x += 3) {
            glm::vec2 p((x + 0.5f) / 32 * 2 - 1, (y + 0.5f) / 32 * 2 - 1);
            ViewWeights direct;
            ASSERT_TRUE(lookup.nearestViews(decodeHemiOctahedral(p), direct));
            EXPECT_LT(blendDistance(direct, table.texels[y * 32 + x]), 1e-6f);
        }
    }
    EXPECT_THROW(lookup.buildTable(0), std::invalid_argument);
    EXPECT_THROW(lookup.buildTable(4096), std::invalid_argument);
}

} // namespace
} // namespace hexlod::impostor
