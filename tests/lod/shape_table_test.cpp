// The shape table's GPU vertex buffer: every mesh of the library once per distinct mesh, its
// positions as stored and its normals in unit scope space, which the LOD4 vertex shader carries
// to a terminal's scope with one division (terminal_mesh.vert) instead of reading the shape's
// nominal size per vertex.
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

TEST_F(ShapeTableTest, MeshNormalsAreUploadedInUnitScopeSpace) {
    // Buildings and trees: shapes of many nominal sizes.
    const testing::TestCity city = testing::makeCity(4, 4);
    ShapeTable table;
    table.upload(*city.meshes);
    // Each distinct mesh once, one after the other: the buffer ends after the last one placed.
    size_t vertexCount = 0;
    for (uint32_t g = 0; g < city.meshes->grammarCount(); ++g)
        for (uint16_t s = 0; s < city.meshes->shapeCount(g); ++s)
            vertexCount = std::max(vertexCount, size_t(table.meshes().at(table.shapeBase(g) + s).baseVertex) +
                                                    city.meshes->mesh(g, s).vertices.size());
    std::vector<render::MeshVertex> uploaded(vertexCount);
    gl::glGetNamedBufferSubData(table.vertexBuffer(), 0,
                                GLsizeiptr(uploaded.size() * sizeof(render::MeshVertex)), uploaded.data());
    size_t checked = 0, stretched = 0;
    std::set<std::tuple<float, float, float>> nominals;
    for (uint32_t g = 0; g < city.meshes->grammarCount(); ++g) {
        for (uint16_t s = 0; s < city.meshes->shapeCount(g); ++s) {
            const render::TerminalMesh& mesh = city.meshes->mesh(g, s);
            const MeshDrawInfo& draw = table.meshes().at(table.shapeBase(g) + s);
            nominals.insert({mesh.nominalSize.x, mesh.nominalSize.y, mesh.nominalSize.z});
            for (size_t v = 0; v < mesh.vertices.size(); ++v) {
                const render::MeshVertex& in = mesh.vertices[v];
                const render::MeshVertex& out = uploaded[size_t(draw.baseVertex) + v];
                EXPECT_EQ(out.position, in.position);
                EXPECT_EQ(out.uv, in.uv);
                EXPECT_EQ(out.rgba, in.rgba);
                const glm::vec3 unit = render::unitSpaceNormal(in.normal, mesh.nominalSize);
                EXPECT_EQ(out.normal, unit) << "grammar " << g << " shape " << s << " vertex " << v;
                // Carried to a scope as the shader does, it is the stored normal's scopeNormal.
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
}

} // namespace
} // namespace hexlod::lod
