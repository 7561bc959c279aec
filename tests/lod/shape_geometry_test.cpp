// Terminal meshes as the LOD4 pass draws them: a double-sided surface (each triangle once per
// side) becomes one triangle with both sides' colours, and anything that is not exactly that
// (an unpaired triangle, curved normals, a degenerate or repeated triangle, bad indices) stays
// as it was. The shipped meshes and their coarse levels are checked against their own triangles.
#include "test_city.h"

#include "hexlod/lod/coarse_meshes.h"
#include "hexlod/lod/shape_geometry.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

namespace hexlod::lod {
namespace {

constexpr uint32_t kFront = 0xff103408u, kBack = 0xff104620u;

// A unit square in the z = 0 plane seen from +z, as two triangles with normal +z, then (when
// `back`) the same two reversed with normal -z, on vertices of their own, as
// render::MeshBuilder::twoSidedQuad emits it.
render::TerminalMesh square(bool back) {
    render::TerminalMesh mesh;
    mesh.shape = "pane";
    mesh.nominalSize = glm::vec3(1.0f, 1.0f, 0.0f);
    const glm::vec3 corners[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (const glm::vec3& p : corners) mesh.vertices.push_back({p, {0, 0, 1}, {0, 0}, kFront});
    mesh.indices = {0, 1, 2, 0, 2, 3};
    if (back) {
        for (const glm::vec3& p : corners) mesh.vertices.push_back({p, {0, 0, -1}, {0, 0}, kBack});
        mesh.indices.insert(mesh.indices.end(), {4, 6, 5, 4, 7, 6});
    }
    return mesh;
}

void expectAsGiven(const ShapeGeometry& geometry, const render::TerminalMesh& mesh) {
    EXPECT_FALSE(geometry.twoSided);
    EXPECT_EQ(geometry.indices, mesh.indices);
    ASSERT_EQ(geometry.vertices.size(), mesh.vertices.size());
    for (size_t v = 0; v < mesh.vertices.size(); ++v) {
        EXPECT_EQ(geometry.vertices[v].position, mesh.vertices[v].position);
        EXPECT_EQ(geometry.vertices[v].normal,
                  render::unitSpaceNormal(mesh.vertices[v].normal, mesh.nominalSize));
        EXPECT_EQ(geometry.vertices[v].rgba, mesh.vertices[v].rgba);
        EXPECT_EQ(geometry.vertices[v].backRgba, mesh.vertices[v].rgba);
    }
}

TEST(ShapeGeometry, ADoubleSidedSquareBecomesTwoTrianglesWithTheBacksColour) {
    const ShapeGeometry geometry = shapeGeometry(square(true));
    EXPECT_TRUE(geometry.twoSided);
    EXPECT_EQ(geometry.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    ASSERT_EQ(geometry.vertices.size(), 4u);
    for (const ShapeVertex& v : geometry.vertices) {
        EXPECT_EQ(v.normal, glm::vec3(0, 0, 1));
        EXPECT_EQ(v.rgba, kFront);
        EXPECT_EQ(v.backRgba, kBack);
    }
}

TEST(ShapeGeometry, OneSidedAndClosedMeshesStayAsGiven) {
    const render::TerminalMesh front = square(false);
    expectAsGiven(shapeGeometry(front), front);
    // A closed tetrahedron: every triangle has neighbours, none its reverse.
    render::TerminalMesh tetrahedron;
    tetrahedron.nominalSize = glm::vec3(2.0f, 1.0f, 0.5f);
    const glm::vec3 p[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const uint32_t faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (const auto& f : faces) {
        const glm::vec3 n = glm::normalize(glm::cross(p[f[1]] - p[f[0]], p[f[2]] - p[f[0]]));
        for (uint32_t i : f) {
            tetrahedron.indices.push_back(uint32_t(tetrahedron.vertices.size()));
            tetrahedron.vertices.push_back({p[i], n, {0, 0}, kFront});
        }
    }
    expectAsGiven(shapeGeometry(tetrahedron), tetrahedron);
}

TEST(ShapeGeometry, AnythingButExactPairsStaysAsGiven) {
    // One triangle without its reverse makes the whole mesh one-sided: drawn without culling,
    // its back would show where the mesh is closed.
    render::TerminalMesh extra = square(true);
    extra.vertices.push_back({{0, 0, 0.5f}, {0, 0, 1}, {0, 0}, kFront});
    extra.vertices.push_back({{1, 0, 0.5f}, {0, 0, 1}, {0, 0}, kFront});
    extra.vertices.push_back({{1, 1, 0.5f}, {0, 0, 1}, {0, 0}, kFront});
    extra.indices.insert(extra.indices.end(), {8, 9, 10});
    expectAsGiven(shapeGeometry(extra), extra);

    // Curved normals: the vertex shader's side test would not be the rasteriser's.
    render::TerminalMesh curved = square(true);
    curved.vertices[0].normal = glm::normalize(glm::vec3(0.3f, 0.0f, 1.0f));
    expectAsGiven(shapeGeometry(curved), curved);

    // Normals that disagree with the winding.
    render::TerminalMesh wound = square(true);
    for (size_t v = 0; v < 4; ++v) wound.vertices[v].normal = glm::vec3(0, 0, -1);
    expectAsGiven(shapeGeometry(wound), wound);

    // The same triangle twice, the same way round: not two sides.
    render::TerminalMesh twice = square(false);
    twice.indices.insert(twice.indices.end(), {0, 1, 2, 0, 2, 3});
    expectAsGiven(shapeGeometry(twice), twice);

    // Degenerate pairs (three points on a line) have no face normal.
    render::TerminalMesh line = square(true);
    for (size_t v : {2u, 6u}) line.vertices[v].position = glm::vec3(0.5f, 0.0f, 0.0f);
    for (size_t v : {3u, 7u}) line.vertices[v].position = glm::vec3(0.25f, 0.0f, 0.0f);
    expectAsGiven(shapeGeometry(line), line);

    // A vertex shared by two faces whose backs differ in colour there cannot carry both.
    render::TerminalMesh shared = square(true);
    shared.vertices.push_back(shared.vertices[6]);
    shared.vertices.back().rgba = kFront;
    shared.indices[11] = 8;
    expectAsGiven(shapeGeometry(shared), shared);
}

TEST(ShapeGeometry, BadAndExtremeMeshesStayAsGivenWithoutFailing) {
    render::TerminalMesh empty;
    expectAsGiven(shapeGeometry(empty), empty);

    render::TerminalMesh ragged = square(true);
    ragged.indices.pop_back();
    expectAsGiven(shapeGeometry(ragged), ragged);

    render::TerminalMesh outOfRange = square(true);
    outOfRange.indices[4] = 1000;
    const ShapeGeometry bad = shapeGeometry(outOfRange);
    EXPECT_FALSE(bad.twoSided);
    EXPECT_EQ(bad.indices, outOfRange.indices);

    for (float value : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        render::TerminalMesh odd = square(true);
        odd.vertices[1].position.x = odd.vertices[5].position.x = value;
        const ShapeGeometry geometry = shapeGeometry(odd);
        EXPECT_FALSE(geometry.twoSided);
        EXPECT_EQ(geometry.indices, odd.indices);
    }

    // A pane 1e6 times larger or smaller still pairs: the test is on positions and directions.
    for (float scale : {1e-6f, 1e6f}) {
        render::TerminalMesh sized = square(true);
        for (render::MeshVertex& v : sized.vertices) v.position *= scale;
        EXPECT_TRUE(shapeGeometry(sized).twoSided) << scale;
    }
}

TEST(ShapeGeometry, ShippedMeshesKeepEveryTriangleOnOneSideOrTheOther) {
    // Each triangle of a shipped mesh is, after pairing, a kept triangle over the same
    // positions: the same way round with its own colour, or reversed with the back colour.
    const testing::TestCity city = testing::makeCity(4, 30);
    std::vector<const render::TerminalMesh*> meshes;
    for (uint32_t g = 0; g < city.meshes->grammarCount(); ++g)
        for (uint16_t s = 0; s < city.meshes->shapeCount(g); ++s) meshes.push_back(&city.meshes->mesh(g, s));
    const std::vector<CoarseMesh> coarse = coarseMeshes(*city.catalog, *city.meshes);
    for (const CoarseMesh& variant : coarse) meshes.push_back(variant.mesh.get());
    size_t twoSided = 0, oneSided = 0, triangles = 0, kept = 0;
    std::set<const render::TerminalMesh*> seen;
    for (const render::TerminalMesh* each : meshes) {
        if (!seen.insert(each).second) continue;
        const render::TerminalMesh& mesh = *each;
        const ShapeGeometry geometry = shapeGeometry(mesh);
        (geometry.twoSided ? twoSided : oneSided) += 1;
        triangles += mesh.indices.size() / 3;
        kept += geometry.indices.size() / 3;
        if (!geometry.twoSided) continue;
        EXPECT_EQ(geometry.indices.size() * 2, mesh.indices.size()) << mesh.shape;
        for (size_t t = 0; t < mesh.indices.size(); t += 3) {
            const render::MeshVertex* in[3];
            for (size_t j = 0; j < 3; ++j) in[j] = &mesh.vertices.at(mesh.indices[t + j]);
            bool found = false;
            for (size_t u = 0; u < geometry.indices.size() && !found; u += 3) {
                const ShapeVertex* out[3];
                for (size_t j = 0; j < 3; ++j) out[j] = &geometry.vertices.at(geometry.indices[u + j]);
                for (size_t k = 0; k < 3 && !found; ++k) {
                    const bool same = out[k]->position == in[0]->position &&
                                      out[(k + 1) % 3]->position == in[1]->position &&
                                      out[(k + 2) % 3]->position == in[2]->position;
                    const bool reverse = out[k]->position == in[0]->position &&
                                         out[(k + 1) % 3]->position == in[2]->position &&
                                         out[(k + 2) % 3]->position == in[1]->position;
                    found =
                        (same && out[k]->rgba == in[0]->rgba) || (reverse && out[k]->backRgba == in[0]->rgba);
                }
            }
            EXPECT_TRUE(found) << mesh.shape << " triangle " << t / 3;
        }
    }
    std::printf("%zu two-sided and %zu one-sided meshes: %zu triangles drawn of %zu\n", twoSided, oneSided,
                kept, triangles);
    EXPECT_GE(twoSided, 2u) << "the leaf and its coarse level are double-sided";
    EXPECT_GT(oneSided, twoSided);
}

} // namespace
} // namespace hexlod::lod
