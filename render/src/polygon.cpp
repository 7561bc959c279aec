// Ear clipping and mitred inward offsets for simple polygons (polygon.h).
#include "hexlod/render/polygon.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace hexlod::render {
namespace {

double cross(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool insideTriangle(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
    return cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0;
}

} // namespace

double signedArea2(std::span<const glm::vec2> polygon) {
    double area = 0.0;
    for (size_t i = 0; i < polygon.size(); ++i) {
        const glm::dvec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
        area += a.x * b.y - a.y * b.x;
    }
    return area;
}

std::vector<uint32_t> triangulatePolygon(std::span<const glm::vec2> polygon) {
    std::vector<uint32_t> triangles;
    if (polygon.size() < 3) return triangles;
    std::vector<uint32_t> remaining(polygon.size());
    std::iota(remaining.begin(), remaining.end(), 0u);
    if (signedArea2(polygon) < 0.0) std::reverse(remaining.begin(), remaining.end());
    const auto at = [&](size_t i) { return glm::dvec2(polygon[remaining[i % remaining.size()]]); };
    // Each pass over the ring either clips an ear or, failing that, clips the flattest corner,
    // so a degenerate polygon still terminates after n - 2 clips.
    while (remaining.size() > 3) {
        const size_t n = remaining.size();
        size_t ear = n, flattest = 0;
        double flattestTurn = -1e300;
        for (size_t i = 0; i < n && ear == n; ++i) {
            const glm::dvec2 a = at(i + n - 1), b = at(i), c = at(i + 1);
            const double turn = cross(a, b, c);
            if (turn > flattestTurn) flattestTurn = turn, flattest = i;
            if (turn <= 0.0) continue;
            bool blocked = false;
            for (size_t j = 0; j < n && !blocked; ++j) {
                if (j == i || j == (i + 1) % n || j == (i + n - 1) % n) continue;
                const glm::dvec2 p = at(j);
                if (p == a || p == b || p == c) continue;
                blocked = insideTriangle(p, a, b, c);
            }
            if (!blocked) ear = i;
        }
        if (ear == n) ear = flattest;
        triangles.insert(triangles.end(),
                         {remaining[(ear + n - 1) % n], remaining[ear], remaining[(ear + 1) % n]});
        remaining.erase(remaining.begin() + static_cast<std::ptrdiff_t>(ear));
    }
    triangles.insert(triangles.end(), remaining.begin(), remaining.end());
    return triangles;
}

std::vector<glm::vec2> insetPolygon(std::span<const glm::vec2> polygon, float distance) {
    const std::vector<glm::vec2> unchanged(polygon.begin(), polygon.end());
    const size_t n = polygon.size();
    if (n < 3 || !(distance > 0.0f) || signedArea2(polygon) <= 0.0) return unchanged;
    std::vector<glm::vec2> out(n);
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec2 prev = polygon[(i + n - 1) % n], here = polygon[i], next = polygon[(i + 1) % n];
        const glm::dvec2 d0 = glm::normalize(here - prev), d1 = glm::normalize(next - here);
        const glm::dvec2 n0(-d0.y, d0.x), n1(-d1.y, d1.x); // inward (left) normals of a CCW ring
        const glm::dvec2 bisector = n0 + n1;
        const double cosHalf = glm::dot(glm::normalize(bisector), n0);
        if (!(glm::length(bisector) > 1e-9) || cosHalf < 0.25) return unchanged; // spike past 4 × distance
        out[i] = glm::vec2(here + glm::normalize(bisector) * (double(distance) / cosHalf));
    }
    for (size_t i = 0; i < n; ++i) {
        const glm::vec2 before = polygon[(i + 1) % n] - polygon[i], after = out[(i + 1) % n] - out[i];
        if (glm::dot(before, after) <= 0.0f) return unchanged;
    }
    if (signedArea2(out) <= 0.0) return unchanged;
    return out;
}

} // namespace hexlod::render
