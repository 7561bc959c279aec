// Ear clipping, insets and the base volumes built with them.
#include "hexlod/render/base_volume_mesh.h"
#include "hexlod/render/polygon.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hexlod::render {
namespace {

double triangulatedArea(const std::vector<glm::vec2>& polygon) {
    const std::vector<uint32_t> t = triangulatePolygon(polygon);
    double area = 0.0;
    for (size_t i = 0; i < t.size(); i += 3) {
        const glm::vec2 tri[3] = {polygon[t[i]], polygon[t[i + 1]], polygon[t[i + 2]]};
        const double a = signedArea2(tri);
        EXPECT_GE(a, 0.0) << "every triangle counter-clockwise";
        area += a;
    }
    return area;
}

TEST(Polygon, TriangulatesConcaveFootprintsInEitherWinding) {
    // An L and a U footprint (as the city generator makes them).
    std::vector<glm::vec2> l = {{0, 0}, {20, 0}, {20, 8}, {8, 8}, {8, 20}, {0, 20}};
    std::vector<glm::vec2> u = {{0, 0}, {30, 0}, {30, 20}, {22, 20}, {22, 8}, {8, 8}, {8, 20}, {0, 20}};
    for (auto* polygon : {&l, &u}) {
        const double area = signedArea2(*polygon);
        EXPECT_EQ(triangulatePolygon(*polygon).size(), 3 * (polygon->size() - 2));
        EXPECT_NEAR(triangulatedArea(*polygon), area, 1e-6);
        std::reverse(polygon->begin(), polygon->end());
        EXPECT_NEAR(triangulatedArea(*polygon), area, 1e-6);
    }
    EXPECT_TRUE(triangulatePolygon(std::vector<glm::vec2>{{0, 0}, {1, 1}}).empty());
    // Collinear and repeated points still terminate with n - 2 triangles.
    const std::vector<glm::vec2> degenerate = {{0, 0}, {1, 0}, {2, 0}, {2, 0}, {1, 0}};
    EXPECT_EQ(triangulatePolygon(degenerate).size(), 9u);
}

TEST(Polygon, InsetsMoveEveryEdgeInwards) {
    const std::vector<glm::vec2> square = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    const std::vector<glm::vec2> in = insetPolygon(square, 1.0f);
    ASSERT_EQ(in.size(), 4u);
    EXPECT_NEAR(in[0].x, 1.0f, 1e-5f);
    EXPECT_NEAR(in[0].y, 1.0f, 1e-5f);
    EXPECT_NEAR(in[2].x, 9.0f, 1e-5f);
    // Too deep an inset turns edges around: the outline stays as it was.
    EXPECT_EQ(insetPolygon(square, 6.0f), square);
    // A clockwise outline is not an outline to inset.
    const std::vector<glm::vec2> clockwise = {{0, 0}, {0, 10}, {10, 10}, {10, 0}};
    EXPECT_EQ(insetPolygon(clockwise, 1.0f), clockwise);
}

// A 20 m x 10 m box of two storey bands, the upper one set back by 2 m, as the business
// grammar's sections are.
grammar::ExtrudedSet steppedTower() {
    grammar::ExtrudedSet set;
    const auto band = [&](float inset, float z, float height, uint32_t rule) {
        const glm::vec2 corners[4] = {
            {inset, inset}, {20 - inset, inset}, {20 - inset, 10 - inset}, {inset, 10 - inset}};
        for (uint32_t i = 0; i < 4; ++i) {
            const glm::vec2 a = corners[i], b = corners[(i + 1) % 4];
            set.elements.push_back({glm::vec3(a, z), glm::vec3(glm::normalize(b - a), 0.0f),
                                    glm::vec3(0, 0, 1), glm::vec2(glm::length(b - a), height), rule, i, 0, 0,
                                    1, 0, 1, 0, 0});
        }
    };
    band(0.0f, 0.0f, 30.0f, 1);
    band(2.0f, 30.0f, 20.0f, 1);
    set.elements.push_back({glm::vec3(0.0f, 0.0f, 30.0f), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0),
                            glm::vec2(20, 0), 2, 0, 0, 0, 1, 0, 1, 0, 0});
    grammar::ExtrudedBuilding building;
    building.elementCount = uint32_t(set.elements.size());
    building.height = 50.0f;
    building.wallMaterial = 3;
    set.buildings.push_back(building);
    return set;
}

TEST(BaseVolumes, FollowTheSetbacksOfTheExtrudedSet) {
    const TerminalMesh m = buildBaseVolumes(steppedTower(), 0.0f);
    // Two bands of four walls and a two-triangle cap each; the zero-height roof edge adds nothing.
    EXPECT_EQ(m.triangleCount(), 2u * (4u * 2u + 2u));
    EXPECT_NEAR(m.boundsMax.z, 50.0f, 1e-4f);
    EXPECT_NEAR(m.boundsMin.x, 0.0f, 1e-5f);
    for (const MeshVertex& v : m.vertices) {
        if (v.position.z > 30.5f) {
            EXPECT_GE(v.position.x, 2.0f - 1e-4f) << "the upper band is set back";
        }
        EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);
        if (v.normal.z < 0.5f) {
            EXPECT_EQ(v.rgba, wallMaterialColour(3));
        }
    }
    // Walls face outwards.
    for (size_t t = 0; t < m.indices.size(); t += 3) {
        const MeshVertex& a = m.vertices[m.indices[t]];
        const glm::vec3 centre(10.0f, 5.0f, a.position.z);
        if (std::abs(a.normal.z) < 0.5f) {
            EXPECT_GT(glm::dot(a.normal, a.position - centre), 0.0f);
        }
    }
    const TerminalMesh inset = buildBaseVolumes(steppedTower(), 0.5f);
    EXPECT_NEAR(inset.boundsMin.x, 0.5f, 1e-4f);
    EXPECT_NEAR(inset.boundsMax.y, 9.5f, 1e-4f);
}

TEST(BaseVolumes, ListEachBuildingsRunOfIndicesAndItsBounds) {
    // The tower, a building with only two walls (no closed band: no triangles, no part), and
    // the tower again 100 m along x.
    const grammar::ExtrudedSet tower = steppedTower();
    grammar::ExtrudedSet set = tower;
    grammar::ExtrudedBuilding open;
    open.firstElement = uint32_t(set.elements.size());
    open.elementCount = 2;
    set.elements.insert(set.elements.end(), tower.elements.begin(), tower.elements.begin() + 2);
    set.buildings.push_back(open);
    grammar::ExtrudedBuilding moved = tower.buildings[0];
    moved.firstElement = uint32_t(set.elements.size());
    for (grammar::ExtrudedElement e : tower.elements) {
        e.origin.x += 100.0f;
        set.elements.push_back(e);
    }
    set.buildings.push_back(moved);

    std::vector<VolumeBuilding> parts;
    const TerminalMesh m = buildBaseVolumes(set, 0.0f, &parts);
    EXPECT_EQ(m.indices, buildBaseVolumes(set, 0.0f).indices) << "listing the parts changes no triangle";
    ASSERT_EQ(parts.size(), 2u);
    EXPECT_EQ(parts[0].firstIndex, 0u);
    EXPECT_EQ(parts[1].firstIndex, parts[0].indexCount);
    EXPECT_EQ(parts[0].indexCount + parts[1].indexCount, m.indices.size());
    EXPECT_EQ(parts[0].indexCount, parts[1].indexCount);
    EXPECT_NEAR(parts[0].boundsMin.x, 0.0f, 1e-4f);
    EXPECT_NEAR(parts[0].boundsMax.x, 20.0f, 1e-4f);
    EXPECT_NEAR(parts[1].boundsMin.x, 100.0f, 1e-4f);
    EXPECT_NEAR(parts[1].boundsMax.z, 50.0f, 1e-4f);
    // The point form's footprint: the lowest band's, 20 x 10 m (not the set-back 16 x 6).
    for (const VolumeBuilding& part : parts) {
        EXPECT_NEAR(part.footprintArea, 200.0f, 1e-3f);
        EXPECT_NEAR(part.footprintPerimeter, 60.0f, 1e-4f);
        EXPECT_EQ(part.wallColour, wallMaterialColour(3));
    }
    for (const VolumeBuilding& part : parts) {
        for (uint32_t i = part.firstIndex; i < part.firstIndex + part.indexCount; ++i) {
            const glm::vec3 p = m.vertices[m.indices[i]].position;
            EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, part.boundsMin)) &&
                        glm::all(glm::lessThanEqual(p, part.boundsMax)));
        }
    }
    // A set without buildings has no part; the list is emptied first.
    buildBaseVolumes(grammar::ExtrudedSet{}, 0.0f, &parts);
    EXPECT_TRUE(parts.empty());
}

} // namespace
} // namespace hexlod::render
