// Pointy-top hex grid in axial coordinates: Red Blob Games, "Hexagonal Grids"
// (https://www.redblobgames.com/grids/hexagons/), sections "Hex to pixel", "Pixel to hex",
// "Rounding to nearest hex", "Rings" and "Spiral rings". Region queries walk hexagon rows and
// confirm each candidate with a separating-axis test against the (convex) query polygon.
#include "hexlod/cells/hex_grid.h"

#include "hexlod/cells/frustum.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace hexlod::cells {
namespace {

constexpr double kSqrt3 = 1.7320508075688772935;

bool finite(glm::dvec2 p) {
    return std::isfinite(p.x) && std::isfinite(p.y);
}

HexCoord add(HexCoord c, HexCoord d, int64_t times = 1) {
    // 64-bit sums narrow by wrapping (defined since C++20) instead of overflowing.
    return {static_cast<int32_t>(c.q + d.q * times), static_cast<int32_t>(c.r + d.r * times)};
}

std::size_t checkedCount(double count, const char* what) {
    if (!(count <= static_cast<double>(kMaxQueryCells)))
        throw std::length_error(std::string(what) + ": more than " + std::to_string(kMaxQueryCells) +
                                " cells");
    return static_cast<std::size_t>(count);
}

// Rounds half up rather than std::round's half away from zero, so the tie rule is the same
// wherever a cell sits (round(x + n) == round(x) + n).
double roundHalfUp(double x) {
    const double down = std::floor(x);
    return x - down >= 0.5 ? down + 1.0 : down;
}

double dot(glm::dvec2 a, glm::dvec2 b) {
    return a.x * b.x + a.y * b.y;
}

// Projection interval of the query polygon on one axis, computed once per query.
struct AxisInterval {
    glm::dvec2 axis;
    double lo, hi;
};

// The three distinct corner offsets of a pointy-top hexagon; the other three are their negatives.
std::array<glm::dvec2, 3> halfCorners(double size) {
    return {{{kSqrt3 * 0.5 * size, -0.5 * size}, {kSqrt3 * 0.5 * size, 0.5 * size}, {0.0, size}}};
}

// Separating-axis test of a convex polygon against hexagons: the axes are the hexagon's three
// edge normals and the polygon's edge normals. Closed sets, so touching counts as meeting.
class PolygonHexTest {
public:
    PolygonHexTest(std::span<const glm::dvec2> polygon, double size) : offsets_(halfCorners(size)) {
        const glm::dvec2 hexNormals[3] = {{1.0, 0.0}, {0.5, 0.5 * kSqrt3}, {-0.5, 0.5 * kSqrt3}};
        for (glm::dvec2 n : hexNormals) axes_.push_back(project(polygon, n));
        for (std::size_t i = 0; i < polygon.size(); ++i) {
            const glm::dvec2 e = polygon[(i + 1) % polygon.size()] - polygon[i];
            if (e.x != 0.0 || e.y != 0.0) axes_.push_back(project(polygon, {-e.y, e.x}));
        }
    }

    bool meets(glm::dvec2 center) const {
        for (const AxisInterval& a : axes_) {
            double extent = 0.0;
            for (glm::dvec2 o : offsets_) extent = std::max(extent, std::abs(dot(o, a.axis)));
            const double c = dot(center, a.axis);
            if (c + extent < a.lo || c - extent > a.hi) return false;
        }
        return true;
    }

private:
    static AxisInterval project(std::span<const glm::dvec2> polygon, glm::dvec2 axis) {
        AxisInterval out{axis, std::numeric_limits<double>::infinity(),
                         -std::numeric_limits<double>::infinity()};
        for (glm::dvec2 p : polygon) {
            out.lo = std::min(out.lo, dot(p, axis));
            out.hi = std::max(out.hi, dot(p, axis));
        }
        return out;
    }

    std::array<glm::dvec2, 3> offsets_;
    std::vector<AxisInterval> axes_;
};

// The x extent of the polygon's boundary inside the strip y0 <= y <= y1 (for any polygon this
// equals the extent of polygon and strip together). Returns false when they do not meet.
bool stripExtent(std::span<const glm::dvec2> polygon, double y0, double y1, double& xMin, double& xMax) {
    xMin = std::numeric_limits<double>::infinity();
    xMax = -xMin;
    auto take = [&](double x) {
        xMin = std::min(xMin, x);
        xMax = std::max(xMax, x);
    };
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const glm::dvec2 a = polygon[i];
        const glm::dvec2 b = polygon[(i + 1) % polygon.size()];
        if (a.y >= y0 && a.y <= y1) take(a.x);
        if (a.y == b.y) continue;
        for (double y : {y0, y1}) {
            const double t = (y - a.y) / (b.y - a.y);
            if (t > 0.0 && t < 1.0) take(a.x + t * (b.x - a.x));
        }
    }
    return xMin <= xMax;
}

} // namespace

std::size_t HexCoordHash::operator()(HexCoord c) const noexcept {
    // splitmix64's finaliser: neighbouring cells land in unrelated buckets.
    uint64_t h = (uint64_t{static_cast<uint32_t>(c.q)} << 32) | static_cast<uint32_t>(c.r);
    h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
    h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
    return static_cast<std::size_t>(h ^ (h >> 31));
}

std::array<HexCoord, 6> neighbours(HexCoord c) {
    std::array<HexCoord, 6> out;
    for (std::size_t i = 0; i < 6; ++i) out[i] = add(c, kHexDirections[i]);
    return out;
}

int64_t distance(HexCoord a, HexCoord b) {
    const int64_t dq = int64_t{a.q} - b.q;
    const int64_t dr = int64_t{a.r} - b.r;
    return std::max({std::abs(dq), std::abs(dr), std::abs(dq + dr)});
}

std::vector<HexCoord> ring(HexCoord center, int32_t radius) {
    if (radius < 0) throw std::invalid_argument("ring: radius must be >= 0, got " + std::to_string(radius));
    if (radius == 0) return {center};
    std::vector<HexCoord> out;
    out.reserve(checkedCount(6.0 * radius, "ring"));
    HexCoord cell = add(center, kHexDirections[4], radius);
    for (HexCoord direction : kHexDirections)
        for (int32_t step = 0; step < radius; ++step) {
            out.push_back(cell);
            cell = add(cell, direction);
        }
    return out;
}

std::vector<HexCoord> spiral(HexCoord center, int32_t radius) {
    if (radius < 0) throw std::invalid_argument("spiral: radius must be >= 0, got " + std::to_string(radius));
    std::vector<HexCoord> out;
    out.reserve(checkedCount(3.0 * radius * (radius + 1.0) + 1.0, "spiral"));
    for (int32_t k = 0; k <= radius; ++k) {
        const std::vector<HexCoord> r = ring(center, k);
        out.insert(out.end(), r.begin(), r.end());
    }
    return out;
}

HexGrid::HexGrid(double circumradius, glm::dvec2 origin)
    : size_(circumradius), width_(kSqrt3 * circumradius), origin_(origin) {
    if (!std::isfinite(circumradius) || !(circumradius > 0.0) || !std::isfinite(width_))
        throw std::invalid_argument("HexGrid: circumradius must be finite and > 0, got " +
                                    std::to_string(circumradius));
    if (!finite(origin)) throw std::invalid_argument("HexGrid: origin must be finite");
}

HexCoord HexGrid::cellOf(glm::dvec2 world) const {
    if (!finite(world)) throw std::invalid_argument("HexGrid::cellOf: world point must be finite");
    const glm::dvec2 local = world - origin_;
    // Fractional cube coordinates times three. In thirds, the corners the arithmetic can hit
    // exactly come out as exact integers (-1, 2, -1 for the top corner of (0, 0)) instead of
    // -0.333..., so their rounding errors tie exactly and the documented order decides.
    const double a = local.x / width_; // columns of hexagon width
    const double b = local.y / size_;
    const double q3 = 3.0 * a - b;
    const double r3 = 2.0 * b;
    const double s3 = -3.0 * a - b;
    const double limit = 3.0 * kMaxCoordinate;
    if (!(std::abs(q3) <= limit && std::abs(r3) <= limit && std::abs(s3) <= limit))
        throw std::out_of_range("HexGrid::cellOf: world point lies beyond the grid's coordinate range");
    double q = roundHalfUp(q3 / 3.0);
    double r = roundHalfUp(r3 / 3.0);
    const double s = roundHalfUp(s3 / 3.0);
    const double dq = std::abs(q3 - 3.0 * q);
    const double dr = std::abs(r3 - 3.0 * r);
    const double ds = std::abs(s3 - 3.0 * s);
    if (dq > dr && dq > ds)
        q = -r - s;
    else if (dr > ds)
        r = -q - s;
    return {static_cast<int32_t>(q), static_cast<int32_t>(r)};
}

glm::dvec2 HexGrid::localCenter(HexCoord c) const {
    return {width_ * (c.q + 0.5 * c.r), 1.5 * size_ * c.r};
}

std::array<glm::dvec2, 6> HexGrid::corners(HexCoord c) const {
    const glm::dvec2 o = center(c);
    const std::array<glm::dvec2, 3> h = halfCorners(size_);
    return {{o + h[0], o + h[1], o + h[2], o - h[0], o - h[1], o - h[2]}};
}

std::vector<HexCoord> HexGrid::cellsInRectangle(glm::dvec2 lo, glm::dvec2 hi) const {
    if (!finite(lo)) throw std::invalid_argument("HexGrid::cellsInRectangle: lo must be finite");
    if (!finite(hi)) throw std::invalid_argument("HexGrid::cellsInRectangle: hi must be finite");
    if (lo.x > hi.x || lo.y > hi.y)
        throw std::invalid_argument("HexGrid::cellsInRectangle: lo must not exceed hi");
    const glm::dvec2 rectangle[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
    return cellsInConvexPolygon(rectangle);
}

std::vector<HexCoord> HexGrid::cellsInConvexPolygon(std::span<const glm::dvec2> points) const {
    if (points.empty())
        throw std::invalid_argument("HexGrid::cellsInConvexPolygon: points must not be empty");
    std::vector<glm::dvec2> local;
    local.reserve(points.size());
    for (glm::dvec2 p : points) {
        if (!finite(p)) throw std::invalid_argument("HexGrid::cellsInConvexPolygon: points must be finite");
        local.push_back(p - origin_);
        if (!finite(local.back()))
            throw std::out_of_range(
                "HexGrid::cellsInConvexPolygon: points lie beyond the grid's coordinate range");
    }
    double yMin = local[0].y, yMax = local[0].y;
    for (glm::dvec2 p : local) {
        yMin = std::min(yMin, p.y);
        yMax = std::max(yMax, p.y);
    }
    const char* name = "HexGrid::cellsInConvexPolygon";
    const double rowPitch = 1.5 * size_;
    // Rows whose hexagons (centre y +- size) reach the polygon's y range; one row of slack each
    // way absorbs rounding, the separating-axis test removes what does not belong.
    const double rLo = std::ceil((yMin - size_) / rowPitch) - 1.0;
    const double rHi = std::floor((yMax + size_) / rowPitch) + 1.0;
    checkedCount(rHi - rLo + 1.0, name);
    const auto outOfRange = [&] {
        return std::out_of_range(std::string(name) + ": area lies beyond the grid's coordinate range");
    };
    if (rLo < -kMaxCoordinate || rHi > kMaxCoordinate) throw outOfRange();

    const PolygonHexTest test(local, size_);
    std::vector<HexCoord> out;
    double examined = 0.0;
    for (auto r = static_cast<int32_t>(rLo); r <= static_cast<int32_t>(rHi); ++r) {
        double xMin, xMax;
        if (!stripExtent(local, rowPitch * r - size_, rowPitch * r + size_, xMin, xMax)) continue;
        const double halfWidth = 0.5 * width_;
        const double qLo = std::ceil((xMin - halfWidth) / width_ - 0.5 * r) - 1.0;
        const double qHi = std::floor((xMax + halfWidth) / width_ - 0.5 * r) + 1.0;
        examined += qHi - qLo + 1.0;
        checkedCount(examined, name);
        if (qLo < -kMaxCoordinate || qHi > kMaxCoordinate) throw outOfRange();
        for (auto q = static_cast<int32_t>(qLo); q <= static_cast<int32_t>(qHi); ++q)
            if (test.meets(localCenter({q, r}))) out.push_back({q, r});
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<HexCoord> HexGrid::cellsInFrustum(const Frustum& frustum, double zMin, double zMax) const {
    if (!std::isfinite(zMin)) throw std::invalid_argument("HexGrid::cellsInFrustum: zMin must be finite");
    if (!std::isfinite(zMax)) throw std::invalid_argument("HexGrid::cellsInFrustum: zMax must be finite");
    if (zMin > zMax) throw std::invalid_argument("HexGrid::cellsInFrustum: zMin must not exceed zMax");
    const std::vector<glm::dvec2> footprint = frustum.footprint(zMin, zMax);
    if (footprint.empty()) return {};
    std::vector<HexCoord> cells = cellsInConvexPolygon(footprint);
    std::erase_if(cells, [&](HexCoord c) { return !frustum.intersectsPrism(center(c), size_, zMin, zMax); });
    return cells;
}

} // namespace hexlod::cells
