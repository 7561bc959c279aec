// View frustum planes and corners from a look-at camera, with conservative culling of boxes and
// hexagonal prisms: plane-versus-corners and then corners-versus-faces, after Inigo Quilez,
// "Correct frustum culling" (https://iquilezles.org/articles/frustumcorrect/). The slab footprint
// clips the frustum's edges to the slab and takes the convex hull (Andrew's monotone chain).
#include "hexlod/cells/frustum.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace hexlod::cells {
namespace {

constexpr double kSqrt3 = 1.7320508075688772935;
// Absorbs rounding in plane distances so a volume touching the frustum is never culled.
constexpr double kSlack = 1e-6;

bool finite(glm::dvec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void require(bool ok, const char* argument, const std::string& why) {
    if (!ok) throw std::invalid_argument(std::string("Frustum: ") + argument + " " + why);
}

// True when every point lies strictly outside the plane: the volume they span is culled.
template <std::size_t N>
bool allOutside(const FrustumPlane& plane, const std::array<glm::dvec3, N>& offsets) {
    for (const glm::dvec3& p : offsets)
        if (glm::dot(plane.normal, p) + plane.offset >= -kSlack) return false;
    return true;
}

// True when the frustum corners all lie beyond lo or all beyond hi along `axis`.
bool cornersOutside(const std::array<glm::dvec3, 8>& corners, glm::dvec3 axis, double lo, double hi) {
    bool allBelow = true, allAbove = true;
    for (const glm::dvec3& c : corners) {
        const double d = glm::dot(c, axis);
        allBelow = allBelow && d < lo - kSlack;
        allAbove = allAbove && d > hi + kSlack;
    }
    return allBelow || allAbove;
}

double cross(glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

std::vector<glm::dvec2> convexHull(std::vector<glm::dvec2> points) {
    std::sort(points.begin(), points.end(),
              [](glm::dvec2 a, glm::dvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    points.erase(std::unique(points.begin(), points.end()), points.end());
    if (points.size() < 3) return points;
    std::vector<glm::dvec2> hull(2 * points.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
        hull[k++] = points[i];
    }
    for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
        hull[k++] = points[i];
    }
    hull.resize(k - 1);
    return hull;
}

} // namespace

Frustum::Frustum(glm::dvec3 position, glm::dvec3 forward, glm::dvec3 up, double fovY, double aspect,
                 double near, double far)
    : eye_(position) {
    require(finite(position), "position", "must be finite");
    require(finite(forward) && glm::length(forward) > 0.0, "forward", "must be finite and non-zero");
    require(finite(up), "up", "must be finite");
    require(std::isfinite(fovY) && fovY > 0.0 && fovY < std::numbers::pi, "fovY",
            "must lie in (0, pi) radians");
    require(std::isfinite(aspect) && aspect > 0.0, "aspect", "must be finite and > 0");
    require(std::isfinite(near) && near > 0.0, "near", "must be finite and > 0");
    require(std::isfinite(far) && far > near, "far", "must be finite and > near");

    const glm::dvec3 f = glm::normalize(forward);
    const glm::dvec3 side = glm::cross(f, up);
    require(glm::length(side) > 1e-12 * glm::length(up), "up", "must not be parallel to forward");
    const glm::dvec3 right = glm::normalize(side);
    const glm::dvec3 u = glm::cross(right, f);
    const double tanY = std::tan(0.5 * fovY);
    const double tanX = aspect * tanY;
    require(std::isfinite(tanX), "aspect", "is too large for this fovY");

    // Side planes pass through the eye; each normal leans from the side axis toward forward.
    planes_[Left] = {glm::normalize(right + tanX * f), 0.0};
    planes_[Right] = {glm::normalize(-right + tanX * f), 0.0};
    planes_[Bottom] = {glm::normalize(u + tanY * f), 0.0};
    planes_[Top] = {glm::normalize(-u + tanY * f), 0.0};
    planes_[Near] = {f, -near};
    planes_[Far] = {-f, far};

    for (int i = 0; i < 2; ++i) {
        const double d = i == 0 ? near : far;
        const glm::dvec3 c = f * d, x = right * (d * tanX), y = u * (d * tanY);
        cornerOffsets_[4 * i + 0] = c - x - y;
        cornerOffsets_[4 * i + 1] = c + x - y;
        cornerOffsets_[4 * i + 2] = c + x + y;
        cornerOffsets_[4 * i + 3] = c - x + y;
    }
}

std::array<glm::dvec3, 8> Frustum::corners() const {
    std::array<glm::dvec3, 8> out;
    for (std::size_t i = 0; i < 8; ++i) out[i] = eye_ + cornerOffsets_[i];
    return out;
}

bool Frustum::contains(glm::dvec3 point) const {
    const glm::dvec3 p = point - eye_;
    for (const FrustumPlane& plane : planes_)
        if (glm::dot(plane.normal, p) + plane.offset < -kSlack) return false;
    return true;
}

bool Frustum::intersectsBox(glm::dvec3 lo, glm::dvec3 hi) const {
    const glm::dvec3 a = lo - eye_, b = hi - eye_;
    const std::array<glm::dvec3, 8> box = {{{a.x, a.y, a.z},
                                            {b.x, a.y, a.z},
                                            {a.x, b.y, a.z},
                                            {b.x, b.y, a.z},
                                            {a.x, a.y, b.z},
                                            {b.x, a.y, b.z},
                                            {a.x, b.y, b.z},
                                            {b.x, b.y, b.z}}};
    for (const FrustumPlane& plane : planes_)
        if (allOutside(plane, box)) return false;
    for (int axis = 0; axis < 3; ++axis) {
        glm::dvec3 n(0.0);
        n[axis] = 1.0;
        if (cornersOutside(cornerOffsets_, n, a[axis], b[axis])) return false;
    }
    return true;
}

bool Frustum::intersectsPrism(glm::dvec2 center, double circumradius, double zMin, double zMax) const {
    const glm::dvec3 c(center.x - eye_.x, center.y - eye_.y, 0.0);
    const double lo = zMin - eye_.z, hi = zMax - eye_.z;
    const double h = 0.5 * kSqrt3 * circumradius, half = 0.5 * circumradius;
    const glm::dvec2 ring[6] = {{h, -half}, {h, half},   {0.0, circumradius},
                                {-h, half}, {-h, -half}, {0.0, -circumradius}};
    std::array<glm::dvec3, 12> prism;
    for (std::size_t i = 0; i < 6; ++i) {
        prism[i] = {c.x + ring[i].x, c.y + ring[i].y, lo};
        prism[i + 6] = {c.x + ring[i].x, c.y + ring[i].y, hi};
    }
    for (const FrustumPlane& plane : planes_)
        if (allOutside(plane, prism)) return false;

    if (cornersOutside(cornerOffsets_, {0.0, 0.0, 1.0}, lo, hi)) return false;
    const glm::dvec3 edgeNormals[3] = {{1.0, 0.0, 0.0}, {0.5, 0.5 * kSqrt3, 0.0}, {-0.5, 0.5 * kSqrt3, 0.0}};
    for (const glm::dvec3& n : edgeNormals) {
        const double mid = glm::dot(c, n);
        if (cornersOutside(cornerOffsets_, n, mid - h, mid + h)) return false;
    }
    return true;
}

std::vector<glm::dvec2> Frustum::footprint(double zMin, double zMax) const {
    const double lo = zMin - eye_.z, hi = zMax - eye_.z;
    static constexpr int kEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                          {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    // The vertices of frustum-and-slab are frustum corners inside the slab and the points where
    // frustum edges cross its planes; their projection's hull is the footprint.
    std::vector<glm::dvec2> points;
    for (const auto& edge : kEdges) {
        const glm::dvec3 a = cornerOffsets_[edge[0]], b = cornerOffsets_[edge[1]];
        double t0 = 0.0, t1 = 1.0;
        if (a.z == b.z) {
            if (a.z < lo || a.z > hi) continue;
        } else {
            double tLo = (lo - a.z) / (b.z - a.z), tHi = (hi - a.z) / (b.z - a.z);
            if (tLo > tHi) std::swap(tLo, tHi);
            t0 = std::max(t0, tLo);
            t1 = std::min(t1, tHi);
            if (t0 > t1) continue;
        }
        for (double t : {t0, t1}) {
            const glm::dvec3 p = a + t * (b - a);
            points.emplace_back(p.x, p.y);
        }
    }
    std::vector<glm::dvec2> hull = convexHull(std::move(points));
    for (glm::dvec2& p : hull) p += glm::dvec2(eye_.x, eye_.y);
    return hull;
}

} // namespace hexlod::cells
