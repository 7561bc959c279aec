// Pairing the two sides of double-sided triangles in a terminal mesh.
#include "hexlod/lod/shape_geometry.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <map>

namespace hexlod::lod {
namespace {

// How close (cosine) a vertex normal must be to its face's normal for the face to count as
// flat: the per-vertex side test can then disagree with the rasteriser's only on a triangle
// seen within about a degree of edge-on, a sliver of a pixel or two.
constexpr float kFlat = 0.9998f;

using PositionKey = std::array<uint32_t, 9>; // a triangle's three positions, as bits, sorted

struct Triangle {
    std::array<uint32_t, 3> index;
    std::array<glm::vec3, 3> position;
};

Triangle triangleAt(const ShapeGeometry& mesh, size_t t) {
    Triangle triangle;
    for (size_t j = 0; j < 3; ++j) {
        triangle.index[j] = mesh.indices[3 * t + j];
        triangle.position[j] = mesh.vertices.at(triangle.index[j]).position;
    }
    return triangle;
}

PositionKey keyOf(const Triangle& t) {
    std::array<std::array<uint32_t, 3>, 3> bits;
    for (size_t j = 0; j < 3; ++j)
        bits[j] = {std::bit_cast<uint32_t>(t.position[j].x), std::bit_cast<uint32_t>(t.position[j].y),
                   std::bit_cast<uint32_t>(t.position[j].z)};
    std::sort(bits.begin(), bits.end());
    PositionKey key;
    for (size_t j = 0; j < 3; ++j) std::copy(bits[j].begin(), bits[j].end(), key.begin() + 3 * j);
    return key;
}

// Whether every vertex normal is the face's normal (by its winding, counter-clockwise seen from
// the side the normal points to). A degenerate triangle has no face normal: it is not flat.
bool flat(const Triangle& t, const std::vector<ShapeVertex>& vertices) {
    const glm::vec3 face = glm::cross(t.position[1] - t.position[0], t.position[2] - t.position[0]);
    const float area = glm::length(face);
    if (!(area > 0.0f) || !std::isfinite(area)) return false;
    for (uint32_t index : t.index) {
        const glm::vec3 n = vertices[index].normal;
        const float length = glm::length(n);
        if (!(length > 0.0f) || glm::dot(n, face) < kFlat * length * area) return false;
    }
    return true;
}

// Whether `u` is `t` in reverse: the same positions, the other way round.
bool reversed(const Triangle& t, const Triangle& u) {
    for (size_t k = 0; k < 3; ++k)
        if (u.position[k] == t.position[0])
            return u.position[(k + 1) % 3] == t.position[2] && u.position[(k + 2) % 3] == t.position[1];
    return false;
}

// The colour of `u`'s vertex at `position`.
uint32_t colourAt(const Triangle& u, const glm::vec3& position, const std::vector<ShapeVertex>& vertices) {
    for (size_t k = 0; k < 3; ++k)
        if (u.position[k] == position) return vertices[u.index[k]].rgba;
    return vertices[u.index[0]].rgba; // unreachable for a reversed pair
}

} // namespace

ShapeGeometry shapeGeometry(const render::TerminalMesh& mesh) {
    ShapeGeometry oneSided;
    oneSided.vertices.reserve(mesh.vertices.size());
    for (const render::MeshVertex& v : mesh.vertices)
        oneSided.vertices.push_back(
            {v.position, render::unitSpaceNormal(v.normal, mesh.nominalSize), v.rgba, v.rgba});
    oneSided.indices = mesh.indices;
    const size_t triangles = mesh.indices.size() / 3;
    if (triangles == 0 || mesh.indices.size() % 3 != 0) return oneSided;
    for (uint32_t index : mesh.indices)
        if (index >= mesh.vertices.size()) return oneSided;

    std::vector<Triangle> all;
    all.reserve(triangles);
    std::map<PositionKey, std::vector<size_t>> byPositions;
    for (size_t t = 0; t < triangles; ++t) {
        all.push_back(triangleAt(oneSided, t));
        if (!flat(all.back(), oneSided.vertices)) return oneSided;
        byPositions[keyOf(all.back())].push_back(t);
    }
    // Each triangle's partner among those over the same positions (in mesh order).
    constexpr size_t kNone = ~size_t(0);
    std::vector<size_t> partner(triangles, kNone);
    for (const auto& [key, candidates] : byPositions) {
        for (size_t t : candidates) {
            if (partner[t] != kNone) continue;
            for (size_t u : candidates) {
                if (u == t || partner[u] != kNone || !reversed(all[t], all[u])) continue;
                partner[t] = u, partner[u] = t;
                break;
            }
            if (partner[t] == kNone) return oneSided;
        }
    }

    // The first of each pair stays, its vertices given the other side's colour.
    ShapeGeometry twoSided;
    twoSided.twoSided = true;
    std::vector<uint32_t> placed(mesh.vertices.size(), ~0u);
    for (size_t t = 0; t < triangles; ++t) {
        if (partner[t] < t) continue;
        const Triangle &front = all[t], &back = all[partner[t]];
        for (size_t j = 0; j < 3; ++j) {
            const uint32_t backRgba = colourAt(back, front.position[j], oneSided.vertices);
            uint32_t& index = placed[front.index[j]];
            if (index == ~0u) {
                index = uint32_t(twoSided.vertices.size());
                ShapeVertex vertex = oneSided.vertices[front.index[j]];
                vertex.backRgba = backRgba;
                twoSided.vertices.push_back(vertex);
            } else if (twoSided.vertices[index].backRgba != backRgba) {
                return oneSided; // a vertex shared by faces whose backs differ in colour
            }
            twoSided.indices.push_back(index);
        }
    }
    return twoSided;
}

} // namespace hexlod::lod
