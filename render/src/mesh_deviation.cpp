// Sampled, appearance-aware Hausdorff distance between two terminal meshes (mesh_deviation.h).
#include "hexlod/render/mesh_deviation.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace hexlod::render {
namespace {

// A sample matches only surface that looks the same: the same colour, within this much per
// linear channel (about 5 levels of 255), and a shading normal within about 37 degrees. A
// generator's coarser level may drop a mullion or merge two materials; plain closest points
// would find the glass right behind the mullion and call that a few millimetres.
constexpr float kColourTolerance = 0.02f;
constexpr float kNormalCosine = 0.8f;

struct Triangle {
    glm::vec3 a, b, c;
    glm::vec4 colour; // the mean of its vertices' colours
    glm::vec3 normal; // the mean of its vertices' shading normals, unit length (zero if they cancel)
};

std::vector<Triangle> trianglesOf(const TerminalMesh& mesh, const glm::vec3& scale) {
    std::vector<Triangle> triangles;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const MeshVertex& a = mesh.vertices.at(mesh.indices[i]);
        const MeshVertex& b = mesh.vertices.at(mesh.indices[i + 1]);
        const MeshVertex& c = mesh.vertices.at(mesh.indices[i + 2]);
        const glm::vec3 normal = a.normal + b.normal + c.normal;
        const float length = glm::length(normal);
        triangles.push_back({scale * a.position, scale * b.position, scale * c.position,
                             (unpackRgba(a.rgba) + unpackRgba(b.rgba) + unpackRgba(c.rgba)) / 3.0f,
                             length > 0.0f ? normal / length : glm::vec3(0.0f)});
    }
    return triangles;
}

bool looksAlike(const Triangle& x, const Triangle& y) {
    const glm::vec4 d = glm::abs(x.colour - y.colour);
    return std::max(std::max(d.r, d.g), std::max(d.b, d.a)) <= kColourTolerance &&
           glm::dot(x.normal, y.normal) >= kNormalCosine;
}

// The closest point of triangle abc to p, by the region of the triangle p projects into
// (Ericson, Real-Time Collision Detection, 5.1.5).
glm::vec3 closestPoint(const glm::vec3& p, const Triangle& t) {
    const glm::vec3 ab = t.b - t.a, ac = t.c - t.a, ap = p - t.a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return t.a;
    const glm::vec3 bp = p - t.b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return t.b;
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return t.a + ab * (d1 / (d1 - d3));
    const glm::vec3 cp = p - t.c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return t.c;
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return t.a + ac * (d2 / (d2 - d6));
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f)
        return t.b + (t.c - t.b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const float denominator = va + vb + vc;
    // A degenerate triangle (no area) has no interior: its edges above already answered.
    if (!(denominator > 0.0f)) return t.a;
    return t.a + ab * (vb / denominator) + ac * (vc / denominator);
}

// The largest per-axis |difference| from each sample of `from` to its closest point on the
// triangles of `to` that look like the sample's own; infinite when none does.
glm::vec3 oneWay(const std::vector<Triangle>& from, const std::vector<Triangle>& to) {
    glm::vec3 worst(0.0f);
    for (const Triangle& t : from) {
        const glm::vec3 samples[] = {t.a,
                                     t.b,
                                     t.c,
                                     0.5f * (t.a + t.b),
                                     0.5f * (t.b + t.c),
                                     0.5f * (t.c + t.a),
                                     (t.a + t.b + t.c) / 3.0f};
        for (const glm::vec3& p : samples) {
            float best = std::numeric_limits<float>::infinity();
            glm::vec3 offset(0.0f);
            for (const Triangle& candidate : to) {
                if (!looksAlike(t, candidate)) continue;
                const glm::vec3 d = closestPoint(p, candidate) - p;
                const float squared = glm::dot(d, d);
                if (squared < best) best = squared, offset = d;
            }
            if (!std::isfinite(best)) return glm::vec3(std::numeric_limits<float>::infinity());
            worst = glm::max(worst, glm::abs(offset));
        }
    }
    return worst;
}

} // namespace

glm::vec3 meshDeviation(const TerminalMesh& a, const TerminalMesh& b) {
    // Closest points are found at the nominal size, where distances are metric: in unit space a
    // thin shape's depth would count many times its real share. An axis of nominal size 0 (a
    // flat shape) is left unscaled.
    glm::vec3 scale = a.nominalSize;
    for (int axis = 0; axis < 3; ++axis)
        if (!(scale[axis] > 0.0f)) scale[axis] = 1.0f;
    const std::vector<Triangle> ta = trianglesOf(a, scale), tb = trianglesOf(b, scale);
    if (ta.empty() != tb.empty()) return glm::vec3(std::numeric_limits<float>::infinity());
    return glm::max(oneWay(ta, tb), oneWay(tb, ta)) / scale;
}

} // namespace hexlod::render
