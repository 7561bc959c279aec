// Geometry primitives for the shape generators (mesh_builder.h).
#include "mesh_builder.h"

#include "hexlod/render/polygon.h"

#include <cmath>
#include <numbers>

namespace hexlod::render {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Any unit vector perpendicular to `axis`.
glm::vec3 perpendicular(const glm::vec3& axis) {
    const glm::vec3 helper = std::abs(axis.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    return glm::normalize(glm::cross(axis, helper));
}

// Outward normal of the edge a -> b of a counter-clockwise polygon.
glm::vec2 edgeOutward(const glm::vec2& a, const glm::vec2& b) {
    const glm::vec2 d = b - a;
    const float length = glm::length(d);
    return length > 0.0f ? glm::vec2(d.y, -d.x) / length : glm::vec2(0.0f);
}

} // namespace

uint32_t MeshBuilder::vertex(const glm::vec3& p, const glm::vec3& n, uint32_t rgba) {
    vertices_.push_back({p, n, glm::vec2(0.0f), rgba});
    return static_cast<uint32_t>(vertices_.size() - 1);
}

void MeshBuilder::orientedTriangle(uint32_t a, uint32_t b, uint32_t c, const glm::vec3& outward) {
    const glm::vec3 n = glm::cross(vertices_[b].position - vertices_[a].position,
                                   vertices_[c].position - vertices_[a].position);
    if (glm::dot(n, outward) < 0.0f) std::swap(b, c);
    indices_.insert(indices_.end(), {a, b, c});
}

void MeshBuilder::polygon(std::span<const glm::vec3> points, const glm::vec3& outward, uint32_t rgba) {
    if (points.size() < 3) return;
    // Newell's normal: robust for any planar polygon, even when its first corners are collinear.
    glm::vec3 newell(0.0f);
    for (size_t i = 0; i < points.size(); ++i) {
        const glm::vec3 &a = points[i], &b = points[(i + 1) % points.size()];
        newell += glm::vec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    const bool flip = glm::dot(newell, outward) < 0.0f;
    const float length = glm::length(newell);
    const glm::vec3 n = length > 0.0f ? (flip ? -newell : newell) / length : glm::normalize(outward);
    const uint32_t first = static_cast<uint32_t>(vertices_.size());
    for (const glm::vec3& p : points) vertex(p, n, rgba);
    for (uint32_t i = 1; i + 1 < points.size(); ++i) {
        if (flip)
            indices_.insert(indices_.end(), {first, first + i + 1, first + i});
        else
            indices_.insert(indices_.end(), {first, first + i, first + i + 1});
    }
}

void MeshBuilder::quad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
                       const glm::vec3& outward, uint32_t rgba) {
    const glm::vec3 points[4] = {a, b, c, d};
    polygon(points, outward, rgba);
}

void MeshBuilder::twoSidedQuad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
                               const glm::vec3& front, uint32_t frontRgba, uint32_t backRgba) {
    quad(a, b, c, d, front, frontRgba);
    quad(a, b, c, d, -front, backRgba);
}

void MeshBuilder::box(const glm::vec3& lo, const glm::vec3& hi, uint32_t rgba, uint32_t faces) {
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int side = 0; side < 2; ++side) {
            if (!(faces & (1u << (2 * axis + side)))) continue;
            glm::vec3 corner[4], outward(0.0f);
            outward[axis] = side ? 1.0f : -1.0f;
            for (int k = 0; k < 4; ++k) {
                corner[k][axis] = side ? hi[axis] : lo[axis];
                corner[k][u] = (k == 1 || k == 2) ? hi[u] : lo[u];
                corner[k][v] = (k >= 2) ? hi[v] : lo[v];
            }
            quad(corner[0], corner[1], corner[2], corner[3], outward, rgba);
        }
    }
}

void MeshBuilder::sweep(const Sweep& s, uint32_t rgba) {
    const std::span<const glm::vec2> start = s.profile;
    const std::span<const glm::vec2> end = s.end.empty() ? s.profile : s.end;
    const size_t n = start.size();
    if (n < 2 || end.size() != n) return;
    // Outward directions are those of a counter-clockwise profile; a clockwise one flips them.
    const float winding = signedArea2(start) >= 0.0 ? 1.0f : -1.0f;
    const auto at = [&](std::span<const glm::vec2> profile, size_t i, float along) {
        return s.pu * profile[i].x + s.pv * profile[i].y + s.axis * along;
    };
    const size_t sides = s.openLast ? n - 1 : n;
    for (size_t i = 0; i < sides; ++i) {
        const size_t j = (i + 1) % n;
        const glm::vec2 o = edgeOutward(start[i], start[j]) * winding * (s.inward ? -1.0f : 1.0f);
        quad(at(start, i, s.s0), at(start, j, s.s0), at(end, j, s.s1), at(end, i, s.s1),
             s.pu * o.x + s.pv * o.y, rgba);
    }
    if (!s.caps || n < 3) return;
    const std::vector<uint32_t> triangles = triangulatePolygon(start);
    // Caps lie in the profile plane, whatever the (possibly slanted) sweep axis.
    glm::vec3 capNormal = glm::normalize(glm::cross(s.pu, s.pv));
    if (glm::dot(capNormal, s.axis) < 0.0f) capNormal = -capNormal;
    for (const auto& [profile, along, outward] :
         {std::tuple{start, s.s0, -capNormal}, std::tuple{end, s.s1, capNormal}}) {
        const uint32_t first = static_cast<uint32_t>(vertices_.size());
        for (size_t i = 0; i < n; ++i) vertex(at(profile, i, along), outward, rgba);
        for (size_t t = 0; t < triangles.size(); t += 3)
            orientedTriangle(first + triangles[t], first + triangles[t + 1], first + triangles[t + 2],
                             outward);
    }
}

void MeshBuilder::ring(std::span<const glm::vec2> outer, std::span<const glm::vec2> inner, float z0, float z1,
                       uint32_t rgba, bool back) {
    const size_t n = outer.size();
    if (n < 3 || inner.size() != n) return;
    sweep({.profile = outer, .axis = {0, 0, 1}, .s0 = z0, .s1 = z1, .caps = false}, rgba);
    sweep({.profile = inner, .axis = {0, 0, 1}, .s0 = z0, .s1 = z1, .caps = false, .inward = true}, rgba);
    for (int face = 0; face < (back ? 2 : 1); ++face) {
        const float z = face ? z0 : z1;
        const glm::vec3 outward(0, 0, face ? -1.0f : 1.0f);
        for (size_t i = 0; i < n; ++i) {
            const size_t j = (i + 1) % n;
            quad(glm::vec3(outer[i], z), glm::vec3(outer[j], z), glm::vec3(inner[j], z),
                 glm::vec3(inner[i], z), outward, rgba);
        }
    }
}

void MeshBuilder::frustum(const glm::vec3& a, const glm::vec3& b, float ra, float rb, int segments, int rings,
                          uint32_t rgba, bool capA, bool capB,
                          const std::function<float(int, int)>& radiusScale) {
    const glm::vec3 axis = glm::normalize(b - a);
    const glm::vec3 e0 = perpendicular(axis), e1 = glm::cross(axis, e0);
    const float length = glm::length(b - a);
    const uint32_t first = static_cast<uint32_t>(vertices_.size());
    for (int r = 0; r <= rings; ++r) {
        const float f = float(r) / float(rings);
        const glm::vec3 centre = a + (b - a) * f;
        for (int k = 0; k < segments; ++k) {
            const float angle = 2.0f * kPi * float(k) / float(segments);
            const glm::vec3 radial = std::cos(angle) * e0 + std::sin(angle) * e1;
            const float radius = (ra + (rb - ra) * f) * (radiusScale ? radiusScale(r, k) : 1.0f);
            vertex(centre + radial * radius, glm::normalize(radial * length + axis * (ra - rb)), rgba);
        }
    }
    for (int r = 0; r < rings; ++r) {
        for (int k = 0; k < segments; ++k) {
            const uint32_t i0 = first + uint32_t(r * segments + k),
                           i1 = first + uint32_t(r * segments + (k + 1) % segments);
            const uint32_t j0 = i0 + uint32_t(segments), j1 = i1 + uint32_t(segments);
            const glm::vec3 outward = vertices_[i0].normal + vertices_[i1].normal;
            orientedTriangle(i0, i1, j1, outward);
            orientedTriangle(i0, j1, j0, outward);
        }
    }
    for (int end = 0; end < 2; ++end) {
        if (!(end ? capB : capA)) continue;
        const glm::vec3 outward = end ? axis : -axis;
        const uint32_t ringStart = first + uint32_t((end ? rings : 0) * segments);
        const uint32_t capFirst = static_cast<uint32_t>(vertices_.size());
        for (int k = 0; k < segments; ++k) vertex(vertices_[ringStart + uint32_t(k)].position, outward, rgba);
        for (int k = 1; k + 1 < segments; ++k)
            orientedTriangle(capFirst, capFirst + uint32_t(k), capFirst + uint32_t(k + 1), outward);
    }
}

void MeshBuilder::sphere(const glm::vec3& centre, const glm::vec3& radii, int slices, int stacks,
                         uint32_t rgba) {
    const uint32_t first = static_cast<uint32_t>(vertices_.size());
    for (int s = 0; s <= stacks; ++s) {
        const float polar = kPi * float(s) / float(stacks);
        for (int k = 0; k < slices; ++k) {
            const float azimuth = 2.0f * kPi * float(k) / float(slices);
            const glm::vec3 unit(std::sin(polar) * std::cos(azimuth), -std::cos(polar),
                                 std::sin(polar) * std::sin(azimuth));
            vertex(centre + unit * radii, glm::normalize(unit / radii), rgba);
        }
    }
    for (int s = 0; s < stacks; ++s) {
        for (int k = 0; k < slices; ++k) {
            const uint32_t i0 = first + uint32_t(s * slices + k),
                           i1 = first + uint32_t(s * slices + (k + 1) % slices);
            const uint32_t j0 = i0 + uint32_t(slices), j1 = i1 + uint32_t(slices);
            const glm::vec3 outward = vertices_[i0].position + vertices_[j1].position - 2.0f * centre;
            if (s > 0) orientedTriangle(i0, i1, j1, outward);          // the bottom cap is a fan
            if (s + 1 < stacks) orientedTriangle(i0, j1, j0, outward); // and so is the top
        }
    }
}

void MeshBuilder::heightField(float x0, float x1, float y0, float y1, int nx, int ny,
                              const std::function<float(float, float)>& z, uint32_t rgba) {
    const uint32_t first = static_cast<uint32_t>(vertices_.size());
    const float dx = (x1 - x0) / float(nx), dy = (y1 - y0) / float(ny);
    for (int j = 0; j <= ny; ++j) {
        for (int i = 0; i <= nx; ++i) {
            const float x = x0 + dx * float(i), y = y0 + dy * float(j);
            const float gx = (z(std::min(x + 0.5f * dx, x1), y) - z(std::max(x - 0.5f * dx, x0), y)) /
                             (std::min(x + 0.5f * dx, x1) - std::max(x - 0.5f * dx, x0));
            const float gy = (z(x, std::min(y + 0.5f * dy, y1)) - z(x, std::max(y - 0.5f * dy, y0))) /
                             (std::min(y + 0.5f * dy, y1) - std::max(y - 0.5f * dy, y0));
            vertex({x, y, z(x, y)}, glm::normalize(glm::vec3(-gx, -gy, 1.0f)), rgba);
        }
    }
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            const uint32_t a = first + uint32_t(j * (nx + 1) + i), b = a + 1, c = a + uint32_t(nx + 1),
                           d = c + 1;
            orientedTriangle(a, b, d, {0, 0, 1});
            orientedTriangle(a, d, c, {0, 0, 1});
        }
    }
}

TerminalMesh MeshBuilder::finish(const std::string& shape, const std::string& source) const {
    TerminalMesh mesh;
    mesh.shape = shape;
    mesh.source = source;
    mesh.nominalSize = size_;
    mesh.indices = indices_;
    mesh.vertices = vertices_;
    const glm::vec3 scale(1.0f / W(), 1.0f / H(), D() > 0.0f ? 1.0f / D() : 0.0f);
    for (MeshVertex& v : mesh.vertices) {
        v.position *= scale;
        // Box projection: the two unit coordinates across the dominant normal axis.
        const glm::vec3 a = glm::abs(v.normal);
        const float t = 0.5f * v.position.z + 0.5f;
        if (a.z >= a.x && a.z >= a.y)
            v.uv = {v.position.x, v.position.y};
        else if (a.x >= a.y)
            v.uv = {t, v.position.y};
        else
            v.uv = {v.position.x, t};
    }
    finalizeMesh(mesh);
    return mesh;
}

Profile& Profile::arc(glm::vec2 centre, glm::vec2 radii, float a0, float a1, int segments) {
    for (int k = 1; k <= segments; ++k) {
        const float angle = glm::radians(a0 + (a1 - a0) * float(k) / float(segments));
        points.push_back(centre + radii * glm::vec2(std::cos(angle), std::sin(angle)));
    }
    return *this;
}

std::vector<glm::vec2> rectangleOutline(float x0, float y0, float x1, float y1) {
    return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

std::vector<glm::vec2> archOutline(float x0, float y0, float x1, float y1, float rise, int arcSegments) {
    // A circular arc through both springing points and the apex, `rise` above the springing line.
    const float half = 0.5f * (x1 - x0), cx = 0.5f * (x0 + x1), spring = y1 - rise;
    const float radius = (half * half + rise * rise) / (2.0f * rise);
    const float centreY = y1 - radius, sweepHalf = std::asin(std::min(1.0f, half / radius));
    std::vector<glm::vec2> outline{{x0, y0}, {x1, y0}, {x1, spring}};
    for (int k = 1; k < arcSegments; ++k) {
        const float angle = sweepHalf - 2.0f * sweepHalf * float(k) / float(arcSegments); // right to left
        outline.push_back({cx + radius * std::sin(angle), centreY + radius * std::cos(angle)});
    }
    outline.push_back({x0, spring});
    return outline;
}

} // namespace hexlod::render
