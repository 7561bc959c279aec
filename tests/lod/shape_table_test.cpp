// The shape table's GPU vertex buffer: every mesh of the library once per distinct mesh, as its
// ShapeGeometry (positions as stored, normals in unit scope space, which the LOD4 vertex shader
// carries to a terminal's scope with one division in terminal_mesh.vert; double-sided surfaces
// once, with both colours), and the runs of shapes drawn with and without face culling.
#include "../render/gl_fixture.h"
#include "test_city.h"

#include "hexlod/lod/shape_table.h"
#include "hexlod/render/gl_api.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cstdio>
#include <set>
#include <tuple>
#include <vector>

namespace hexlod::lod {
namespace {

class ShapeTableTest : public render::GlTest {};

TEST_F(ShapeTableTest, MeshesAreUploadedAsTheirShapeGeometry) {
    // Buildings and trees: shapes of many nominal sizes, double-sided leaves among them.
    const testing::TestCity city = testing::makeCity(4, 4);
    ShapeTable table;
    table.upload(*city.meshes);
    // Each distinct mesh once, one after the other: the buffer ends after the last one placed.
    size_t vertexCount = 0;
    for (uint32_t g = 0; g < city.meshes->grammarCount(); ++g)
        for (uint16_t s = 0; s < city.meshes->shapeCount(g); ++s)
            vertexCount = std::max(vertexCount, size_t(table.meshes().at(table.shapeBase(g) + s).baseVertex) +
                                                    shapeGeometry(city.meshes->mesh(g, s)).vertices.size());
    std::vector<ShapeVertex> uploaded(vertexCount);
    gl::glGetNamedBufferSubData(table.vertexBuffer(), 0, GLsizeiptr(uploaded.size() * sizeof(ShapeVertex)),
                                uploaded.data());
    std::vector<bool> twoSided;
    size_t checked = 0, stretched = 0;
    std::set<std::tuple<float, float, float>> nominals;
    for (uint32_t g = 0; g < city.meshes->grammarCount(); ++g) {
        for (uint16_t s = 0; s < city.meshes->shapeCount(g); ++s) {
            const render::TerminalMesh& mesh = city.meshes->mesh(g, s);
            const ShapeGeometry geometry = shapeGeometry(mesh);
            const MeshDrawInfo& draw = table.meshes().at(table.shapeBase(g) + s);
            EXPECT_EQ(draw.indexCount, geometry.indices.size());
            EXPECT_EQ(table.triangles(table.shapeBase(g) + s), geometry.indices.size() / 3);
            twoSided.push_back(geometry.twoSided);
            nominals.insert({mesh.nominalSize.x, mesh.nominalSize.y, mesh.nominalSize.z});
            for (size_t v = 0; v < geometry.vertices.size(); ++v) {
                const ShapeVertex& out = uploaded[size_t(draw.baseVertex) + v];
                EXPECT_EQ(out.position, geometry.vertices[v].position);
                EXPECT_EQ(out.normal, geometry.vertices[v].normal) << "grammar " << g << " shape " << s;
                EXPECT_EQ(out.rgba, geometry.vertices[v].rgba);
                EXPECT_EQ(out.backRgba, geometry.vertices[v].backRgba);
                if (geometry.twoSided) continue;
                // Carried to a scope as the shader does, it is the stored normal's scopeNormal.
                const render::MeshVertex& in = mesh.vertices[v];
                const glm::vec3 scope = 1.7f * mesh.nominalSize + glm::vec3(0.3f, 0.9f, 0.2f);
                const glm::vec3 shader = glm::normalize(out.normal / glm::max(scope, glm::vec3(1e-4f)));
                EXPECT_LT(glm::length(shader - render::scopeNormal(in.normal, mesh.nominalSize, scope)),
                          1e-5f);
                stretched += glm::length(out.normal - in.normal) > 1e-3f;
                ++checked;
            }
        }
    }
    std::printf("%zu vertices of %zu nominal sizes checked, %zu of their normals changed by unit space\n",
                checked, nominals.size(), stretched);
    EXPECT_GT(checked, 100u);
    EXPECT_GT(nominals.size(), 3u);
    EXPECT_GT(stretched, 0u) << "no shape's nominal size stretches its normals: the test proves nothing";

    // The runs cover every shape in order, each run alike, two neighbours never alike.
    std::vector<bool> fromRuns;
    for (size_t r = 0; r < table.sidedRuns().size(); ++r) {
        const SidedRun& run = table.sidedRuns()[r];
        EXPECT_EQ(run.first, fromRuns.size());
        EXPECT_GT(run.count, 0u);
        if (r > 0) {
            EXPECT_NE(run.twoSided, table.sidedRuns()[r - 1].twoSided);
        }
        fromRuns.insert(fromRuns.end(), run.count, run.twoSided);
    }
    EXPECT_EQ(fromRuns, twoSided);
    EXPECT_NE(std::count(twoSided.begin(), twoSided.end(), true), 0) << "no two-sided shape: leaves are";
}

} // namespace
} // namespace hexlod::lod
