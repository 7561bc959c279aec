// A terminal shape's mesh in *unit scope space*: the contract between the mesh library, the
// renderer, the impostor baker and the glTF exporter. One mesh per terminal shape is drawn
// instanced over every terminal record of that shape (thesis §7.3, LOD4).
//
// Unit scope space. A terminal record has a scope: an origin corner, orthonormal axes X (along
// the facade), Y (up the facade), Z (out of the facade), a width w, a height h and a depth
// d = depthRatio × min(w, h). A vertex at unit position (u, v, t) lands at
//     origin + u·w·X + v·h·Y + t·d·Z,
// that is T·R·S with S = diag(w, h, d). Every mesh keeps u, v in [0, 1] and t in [-1, 1]:
// t = +1 is the shape's full protrusion out of the wall plane, t < 0 recedes behind it (glass
// in its reveal, a door set back). A shape whose nominal depth is 0 (the `wall` tile) is flat
// at t = 0.
//
// Normals are stored as the shape's metric normals at its *nominal* size N = (W, H, D): the
// `shape` declaration's width and height and D = depth_ratio × min(W, H). The shape drawn at
// N is diag(N)·p, so for a terminal of size s = (w, h, d) the mesh is stretched by s / N
// relative to that, and its normal is
//     n_world = normalize(R · (N / s) ⊙ n)          (the inverse transpose of diag(s / N)),
// which is what scopeNormal() computes. Equivalently, unitSpaceNormal() turns a stored normal
// into the normal of the unit-space mesh, which the inverse transpose of diag(w, h, d) then
// carries to the world, as glTF viewers do with a node's scale. A component of N that is 0
// (flat shapes, whose normals are ±t only) is treated as a ratio of 1.
#pragma once

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace hexlod::render {

// 36 bytes, interleaved and tightly packed; the GL side binds the members as attributes 0..3.
struct MeshVertex {
    glm::vec3 position; // unit scope space
    glm::vec3 normal;   // unit length, metric shape space at the nominal size
    glm::vec2 uv;
    uint32_t rgba; // linear RGBA8, material baked in, R in the low byte
};
static_assert(sizeof(MeshVertex) == 36, "MeshVertex is bound as a tightly packed 36-byte stride");

struct TerminalMesh {
    std::string shape; // the grammar's shape name
    std::vector<MeshVertex> vertices;
    std::vector<uint32_t> indices;              // triangle list, counter-clockwise front faces
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f}; // unit scope space
    glm::vec3 nominalSize{1.0f};                // (W, H, D) the normals are metric at, metres
    uint64_t contentHash = 0;                   // of vertices + indices bytes only: keys impostor bakes
    std::string source;                         // "procedural", "fallback" or the glTF path it came from

    size_t triangleCount() const { return indices.size() / 3; }
    size_t byteSize() const {
        return vertices.size() * sizeof(MeshVertex) + indices.size() * sizeof(uint32_t);
    }
};

// Packs linear colour components in [0, 1] into MeshVertex::rgba (R in the low byte).
uint32_t packRgba(float r, float g, float b, float a = 1.0f);
glm::vec4 unpackRgba(uint32_t rgba);

// The bounds of the vertices' positions; with no vertex, lo > hi.
void vertexBounds(std::span<const MeshVertex> vertices, glm::vec3& lo, glm::vec3& hi);

// Recomputes boundsMin/boundsMax (zero with no vertex) and contentHash from the vertices and
// indices.
void finalizeMesh(TerminalMesh& mesh);

// The nominal size of a declared shape: (width, height, depthRatio × min(width, height)).
glm::vec3 nominalShapeSize(float width, float height, float depthRatio);

// World-space normal (before the rotation R) of a stored normal on a terminal of scope size
// `scopeSize` = (w, h, d); see the header comment. Never NaN: a zero result gives +t.
glm::vec3 scopeNormal(const glm::vec3& storedNormal, const glm::vec3& nominalSize,
                      const glm::vec3& scopeSize);
// The stored normal as a normal of the unit-space mesh (unit length).
glm::vec3 unitSpaceNormal(const glm::vec3& storedNormal, const glm::vec3& nominalSize);

} // namespace hexlod::render
