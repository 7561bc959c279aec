#include "hexlod/grammar/footprint.h"

#include <algorithm>
#include <cmath>

namespace hexlod::grammar {
namespace {

double cross(const glm::dvec2& a, const glm::dvec2& b) {
    return a.x * b.y - a.y * b.x;
}

double signedArea(const std::vector<glm::dvec2>& p) {
    // Shoelace relative to the first point keeps precision far from the origin.
    double twiceArea = 0.0;
    for (size_t i = 1; i + 1 < p.size(); ++i) twiceArea += cross(p[i] - p[0], p[i + 1] - p[0]);
    return 0.5 * twiceArea;
}

int orientation(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    const double v = cross(b - a, c - a);
    return (v > 0) - (v < 0);
}

bool onSegment(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& p) {
    return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
           p.y <= std::max(a.y, b.y);
}

bool segmentsMeet(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, const glm::dvec2& d) {
    const int o1 = orientation(a, b, c), o2 = orientation(a, b, d);
    const int o3 = orientation(c, d, a), o4 = orientation(c, d, b);
    if (o1 != o2 && o3 != o4) return true;
    return (o1 == 0 && onSegment(a, b, c)) || (o2 == 0 && onSegment(a, b, d)) ||
           (o3 == 0 && onSegment(c, d, a)) || (o4 == 0 && onSegment(c, d, b));
}

} // namespace

bool isSelfIntersecting(const std::vector<glm::dvec2>& p) {
    const size_t n = p.size();
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec2 &a = p[i], &b = p[(i + 1) % n];
        for (size_t j = i + 2; j < n; ++j) {
            if (i == 0 && j == n - 1) continue; // edges n-1 and 0 share a vertex
            if (segmentsMeet(a, b, p[j], p[(j + 1) % n])) return true;
        }
    }
    return false;
}

bool cleanFootprint(const std::vector<glm::dvec2>& raw, CleanFootprint& out, std::string& error) {
    out = CleanFootprint{};
    for (const glm::dvec2& point : raw) {
        if (!std::isfinite(point.x) || !std::isfinite(point.y)) {
            error = "footprint has a non-finite coordinate";
            return false;
        }
    }
    if (raw.empty()) {
        error = "footprint is empty";
        return false;
    }
    glm::dvec2 lo = raw[0], hi = raw[0];
    for (const glm::dvec2& point : raw) lo = glm::min(lo, point), hi = glm::max(hi, point);
    const double extent = glm::length(hi - lo);
    // Tolerances scale with the footprint so that a 1 cm shed and a 1 km mall clean alike;
    // 1e-9 of the extent stays far above double rounding even 1e7 m from the origin.
    const double duplicateTolerance = 1e-9 * extent;
    const double collinearTolerance = 1e-7 * extent;

    std::vector<glm::dvec2> points;
    points.reserve(raw.size());
    for (const glm::dvec2& point : raw) {
        if (points.empty() || glm::length(point - points.back()) > duplicateTolerance)
            points.push_back(point);
    }
    while (points.size() > 1 && glm::length(points.front() - points.back()) <= duplicateTolerance)
        points.pop_back();

    // Drop points that lie on the line through their neighbours (including spikes that
    // double back); repeat until stable because each removal can expose another.
    for (bool changed = true; changed && points.size() >= 3;) {
        changed = false;
        for (size_t i = 0; i < points.size() && points.size() >= 3; ++i) {
            const glm::dvec2& prev = points[(i + points.size() - 1) % points.size()];
            const glm::dvec2& next = points[(i + 1) % points.size()];
            const glm::dvec2 base = next - prev;
            const double baseLength = glm::length(base);
            const double distance = baseLength > duplicateTolerance
                                        ? std::fabs(cross(base, points[i] - prev)) / baseLength
                                        : glm::length(points[i] - prev);
            if (distance <= collinearTolerance) {
                points.erase(points.begin() + static_cast<std::ptrdiff_t>(i));
                changed = true;
                --i;
            }
        }
    }
    out.removedPoints = raw.size() - points.size();
    if (points.size() < 3) {
        error = "footprint has fewer than 3 distinct, non-collinear points";
        return false;
    }
    double area = signedArea(points);
    if (!(std::fabs(area) > 1e-12 * extent * extent)) {
        error = "footprint has zero area";
        return false;
    }
    if (area < 0) {
        std::reverse(points.begin(), points.end());
        area = -area;
        out.reversed = true;
    }
    out.selfIntersecting = isSelfIntersecting(points);
    out.area = area;
    out.points = std::move(points);
    return true;
}

} // namespace hexlod::grammar
