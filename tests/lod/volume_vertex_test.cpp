// Base volumes as the GPU holds them: normals in 10-bit signed components within a 511th of
// the unit vector they pack (extreme and non-finite components clamped), walls' elements
// kept and -1 elsewhere, 16-bit indices below 65,536 vertices and 32-bit ones from there,
// and a real batch's shell in about two thirds of the bytes a MeshVertex mesh takes.
#include "../render/gl_fixture.h"
#include "test_city.h"

#include "hexlod/lod/volume_vertex.h"
#include "hexlod/render/base_volume_mesh.h"
#include "hexlod/render/gl_api.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>

namespace hexlod::lod {
namespace {

TEST(VolumeVertex, NormalsPackToTenBitsEachAndBack) {
    for (const glm::vec3& axis : {glm::vec3(1, 0, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, 1)})
        EXPECT_EQ(unpackSnorm10(packSnorm10(axis)), axis);
    std::mt19937 random(11);
    std::normal_distribution<float> gauss;
    float worst = 0.0f;
    for (int i = 0; i < 10000; ++i) {
        const glm::vec3 n = glm::normalize(glm::vec3(gauss(random), gauss(random), gauss(random)));
        const uint32_t packed = packSnorm10(n);
        EXPECT_EQ(packed >> 30, 0u);
        const glm::vec3 back = unpackSnorm10(packed);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(back[c] - n[c]));
    }
    EXPECT_LE(worst, 0.5f / 511.0f + 1e-6f);
    // Out of range, infinite or NaN components: clamped, or 0.
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(unpackSnorm10(packSnorm10({3.0f, -inf, nan})), glm::vec3(1.0f, -1.0f, 0.0f));
    EXPECT_EQ(unpackSnorm10(packSnorm10({inf, -2.0f, 0.0f})), glm::vec3(1.0f, -1.0f, 0.0f));
}

TEST(VolumeVertex, WallsKeepTheirElementAndCapsAreMinusOne) {
    const std::vector<render::MeshVertex> vertices = {
        {{1.5f, -2.0f, 3.0f}, {0, -1, 0}, {17.0f, 1.0f}, 0xff102030u},
        {{1e4f, 2e4f, 300.0f}, {0, 0, 1}, {-1.0f, 0.0f}, 0xff405060u},
    };
    const std::vector<VolumeVertex> packed = packVolumeVertices(vertices);
    ASSERT_EQ(packed.size(), 2u);
    EXPECT_EQ(packed[0].position, vertices[0].position);
    EXPECT_EQ(packed[0].element, 17.0f);
    EXPECT_EQ(packed[0].rgba, vertices[0].rgba);
    EXPECT_EQ(unpackSnorm10(packed[0].normal), vertices[0].normal);
    EXPECT_EQ(packed[1].position, vertices[1].position);
    EXPECT_EQ(packed[1].element, -1.0f);
}

class VolumeVertexGl : public render::GlTest {};

// The buffers read back as packed, with the index width the vertex count allows.
void expectUploaded(const render::TerminalMesh& mesh, uint32_t indexSize) {
    VolumeBuffers gpu = uploadVolumeMesh(mesh);
    EXPECT_NE(gpu.vao, 0u);
    EXPECT_EQ(gpu.indexSize, indexSize);
    EXPECT_EQ(gpu.indexType, indexSize == 2 ? uint32_t(GL_UNSIGNED_SHORT) : uint32_t(GL_UNSIGNED_INT));
    EXPECT_EQ(gpu.bytes, mesh.vertices.size() * sizeof(VolumeVertex) + mesh.indices.size() * indexSize);
    std::vector<VolumeVertex> vertices(mesh.vertices.size());
    gl::glGetNamedBufferSubData(gpu.vertexBuffer, 0, GLsizeiptr(vertices.size() * sizeof(VolumeVertex)),
                                vertices.data());
    const std::vector<VolumeVertex> expected = packVolumeVertices(mesh.vertices);
    for (size_t v = 0; v < vertices.size(); ++v) {
        EXPECT_EQ(vertices[v].position, expected[v].position);
        EXPECT_EQ(vertices[v].normal, expected[v].normal);
        EXPECT_EQ(vertices[v].element, expected[v].element);
        EXPECT_EQ(vertices[v].rgba, expected[v].rgba);
    }
    std::vector<uint8_t> bytes(mesh.indices.size() * indexSize);
    gl::glGetNamedBufferSubData(gpu.indexBuffer, 0, GLsizeiptr(bytes.size()), bytes.data());
    for (size_t i = 0; i < mesh.indices.size(); ++i) {
        uint32_t index = 0;
        std::memcpy(&index, bytes.data() + i * indexSize, indexSize); // little-endian
        EXPECT_EQ(index, mesh.indices[i]) << "index " << i;
    }
    releaseVolumeMesh(gpu);
    EXPECT_EQ(gpu.vao, 0u);
}

TEST_F(VolumeVertexGl, IndicesAreSixteenBitsBelow65536VerticesAndThirtyTwoFromThere) {
    for (uint32_t count : {3u, 65536u, 65537u}) {
        render::TerminalMesh mesh;
        mesh.vertices.assign(count, render::MeshVertex{{0, 0, 0}, {0, 0, 1}, {-1, 0}, 0xffffffffu});
        for (uint32_t v = 0; v < count; ++v) mesh.vertices[v].position = glm::vec3(float(v), 0.0f, 0.0f);
        mesh.indices = {0, 1, count - 1, count - 1, 1, 2};
        expectUploaded(mesh, count <= 65536 ? 2 : 4);
    }
}

TEST_F(VolumeVertexGl, ARealBatchsShellTakesAboutTwoThirdsOfTheBytes) {
    testing::TestCity city = testing::makeCity(40, 0);
    render::TerminalMesh shell; // the largest batch's
    for (uint32_t b = 0; b < city.catalog->batchCount(); ++b) {
        render::TerminalMesh each = render::buildBaseVolumes(city.catalog->expandExtruded(b), 0.0f);
        if (each.indices.size() > shell.indices.size()) shell = std::move(each);
    }
    ASSERT_GT(shell.indices.size(), 1000u);
    expectUploaded(shell, 2);
    size_t walls = 0;
    for (const VolumeVertex& v : packVolumeVertices(shell.vertices)) walls += v.element >= 0.0f;
    EXPECT_GT(walls, 0u);
    const double packed = double(shell.vertices.size() * sizeof(VolumeVertex) + shell.indices.size() * 2);
    std::printf("shell of %zu vertices: %.0f bytes packed, %zu as MeshVertex\n", shell.vertices.size(),
                packed, shell.byteSize());
    EXPECT_LT(packed, 0.7 * double(shell.byteSize()));
}

} // namespace
} // namespace hexlod::lod
