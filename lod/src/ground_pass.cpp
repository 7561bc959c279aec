#include "hexlod/lod/ground_pass.h"
#include "hexlod/render/gl_api.h"
#include "hexlod/render/mesh_vertex_format.h"
#include "hexlod/render/terminal_mesh.h"

#include <glm/geometric.hpp>

#include <vector>

namespace hexlod::lod {
namespace {

constexpr float kGroundExtent = 30000.0f; // metres each way: beyond the fog's reach
constexpr float kRoadLift = 0.03f;        // above the ground, so the two do not fight for depth

void uploadMesh(uint32_t& vao, uint32_t& vertexBuffer, uint32_t& indexBuffer,
                const std::vector<render::MeshVertex>& vertices, const std::vector<uint32_t>& indices) {
    gl::glCreateBuffers(1, &vertexBuffer);
    gl::glNamedBufferStorage(vertexBuffer,
                             GLsizeiptr(std::max<size_t>(vertices.size(), 1) * sizeof(render::MeshVertex)),
                             vertices.empty() ? nullptr : vertices.data(), 0);
    gl::glCreateBuffers(1, &indexBuffer);
    gl::glNamedBufferStorage(indexBuffer, GLsizeiptr(std::max<size_t>(indices.size(), 1) * sizeof(uint32_t)),
                             indices.empty() ? nullptr : indices.data(), 0);
    gl::glCreateVertexArrays(1, &vao);
    gl::glVertexArrayVertexBuffer(vao, 0, vertexBuffer, 0, sizeof(render::MeshVertex));
    gl::glVertexArrayElementBuffer(vao, indexBuffer);
    render::setMeshVertexFormat(vao, 0);
}

void addQuad(std::vector<render::MeshVertex>& vertices, std::vector<uint32_t>& indices,
             const glm::vec3 corners[4], uint32_t colour) {
    const uint32_t base = uint32_t(vertices.size());
    for (int i = 0; i < 4; ++i) vertices.push_back({corners[i], glm::vec3(0, 0, 1), glm::vec2(0.0f), colour});
    for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(base + i);
}

} // namespace

GroundPass::~GroundPass() {
    for (uint32_t vao : {groundVao_, roadVao_})
        if (vao) gl::glDeleteVertexArrays(1, &vao);
    for (uint32_t buffer : buffers_)
        if (buffer) gl::glDeleteBuffers(1, &buffer);
}

void GroundPass::upload(std::span<const scene::RoadSegment> roads, const glm::dvec3& origin) {
    origin_ = origin;
    std::vector<render::MeshVertex> vertices;
    std::vector<uint32_t> indices;
    const glm::vec3 ground[4] = {{-kGroundExtent, -kGroundExtent, 0},
                                 {kGroundExtent, -kGroundExtent, 0},
                                 {kGroundExtent, kGroundExtent, 0},
                                 {-kGroundExtent, kGroundExtent, 0}};
    addQuad(vertices, indices, ground, render::packRgba(0.42f, 0.44f, 0.36f));
    uploadMesh(groundVao_, buffers_[0], buffers_[1], vertices, indices);
    vertices.clear();
    indices.clear();
    const uint32_t asphalt = render::packRgba(0.22f, 0.22f, 0.23f);
    for (const scene::RoadSegment& road : roads) {
        const glm::dvec2 along = road.b - road.a;
        if (!(glm::length(along) > 0.0) || !(road.width > 0.0)) continue;
        const glm::dvec2 side = glm::normalize(glm::dvec2(-along.y, along.x)) * (0.5 * road.width);
        const glm::dvec2 a = road.a - glm::dvec2(origin), b = road.b - glm::dvec2(origin);
        const glm::vec3 corners[4] = {{glm::vec2(a - side), kRoadLift},
                                      {glm::vec2(b - side), kRoadLift},
                                      {glm::vec2(b + side), kRoadLift},
                                      {glm::vec2(a + side), kRoadLift}};
        addQuad(vertices, indices, corners, asphalt);
    }
    roadIndices_ = uint32_t(indices.size());
    uploadMesh(roadVao_, buffers_[2], buffers_[3], vertices, indices);
    bytes_ = (4 + vertices.size()) * sizeof(render::MeshVertex) + (6 + indices.size()) * sizeof(uint32_t);
}

uint64_t GroundPass::draw(const render::ShaderProgram& program, const glm::dvec3& camera) const {
    program.use();
    // The plane follows the camera in x and y, so it never ends where the camera can see.
    program.set("cellOffset", glm::vec3(0.0f, 0.0f, float(origin_.z - camera.z)));
    gl::glBindVertexArray(groundVao_);
    gl::glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_INT, nullptr);
    uint64_t triangles = 2;
    if (roadIndices_ > 0) {
        program.set("cellOffset", glm::vec3(origin_ - camera));
        gl::glBindVertexArray(roadVao_);
        gl::glDrawElements(GL_TRIANGLES, GLsizei(roadIndices_), GL_UNSIGNED_INT, nullptr);
        triangles += roadIndices_ / 3;
    }
    gl::glBindVertexArray(0);
    return triangles;
}

} // namespace hexlod::lod
