#include "city_lots.h"

#include "footprint_shapes.h"

#include <algorithm>
#include <cmath>

namespace hexlod::scene::detail {
namespace {

using grammar::combineKey;

constexpr uint64_t kDepthTag = 0xde97ull;

// Cuts [0, length) into pieces of about `lotWidth`; every cut is jittered by up to a fifth
// of a piece, so pieces keep at least 60% of the mean and never reorder.
template <typename Emit> void cutStrip(double length, double lotWidth, uint64_t key, Emit&& emit) {
    const int pieces = std::max(1, static_cast<int>(std::lround(length / lotWidth)));
    Draws draw{key};
    double start = 0.0;
    for (int k = 1; k <= pieces; ++k) {
        const double end = k == pieces ? length : length * (k + draw.uniform(-0.2, 0.2)) / pieces;
        emit(start, end);
        start = end;
    }
}

Polygon chamfered(double w, double d, double cut) {
    return {{cut, 0}, {w - cut, 0}, {w, cut}, {w, d - cut}, {w - cut, d}, {cut, d}, {0, d - cut}, {0, cut}};
}

// The largest w:d rectangle turned by `angle` whose bounding box still fits w x d.
Polygon rotatedBox(double w, double d, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    const double ac = std::abs(c), as = std::abs(s);
    const double k = std::min(w / (w * ac + d * as), d / (w * as + d * ac));
    const double hw = 0.5 * w * k, hd = 0.5 * d * k;
    Polygon p;
    for (const glm::dvec2 corner : {glm::dvec2(-hw, -hd), {hw, -hd}, {hw, hd}, {-hw, hd}})
        p.push_back({0.5 * w + c * corner.x - s * corner.y, 0.5 * d + s * corner.x + c * corner.y});
    return p;
}

// A regular polygon stretched to the lot: convex, so it stays within the ellipse's box.
Polygon stretchedPolygon(double w, double d, int sides, double phase) {
    Polygon p;
    for (int i = 0; i < sides; ++i) {
        const double angle = phase + 2.0 * M_PI * i / sides;
        p.push_back({0.5 * w * (1.0 + std::cos(angle)), 0.5 * d * (1.0 + std::sin(angle))});
    }
    return p;
}

// Mirrors across the lot's centre line; reversing keeps the polygon counter-clockwise.
Polygon mirrored(Polygon p, double w) {
    for (glm::dvec2& q : p) q.x = w - q.x;
    std::reverse(p.begin(), p.end());
    return p;
}

Polygon drawShape(double w, double d, Draws& draw) {
    const double pick = draw.uniform(0.0, 1.0);
    const double shortSide = std::min(w, d);
    if (pick < 0.38) return box(w, d * draw.uniform(0.6, 1.0));
    if (pick < 0.48) return rotatedBox(w, d, draw.uniform(-0.45, 0.45));
    if (pick < 0.63) {
        Polygon l = lShape(w, d, draw.uniform(0.35, 0.6) * shortSide);
        return draw.uniform(0.0, 1.0) < 0.5 ? l : mirrored(std::move(l), w);
    }
    if (pick < 0.71) return uShape(w, d, draw.uniform(0.25, 0.33) * shortSide);
    if (pick < 0.79) return tShape(w, d, draw.uniform(0.3, 0.5) * w);
    if (pick < 0.90) return chamfered(w, d, draw.uniform(0.15, 0.3) * shortSide);
    return stretchedPolygon(w, d, 5 + static_cast<int>(draw.uniform(0.0, 6.0)),
                            draw.uniform(0.0, 2.0 * M_PI));
}

// Lot-local (u along the frontage, v away from the street) to world; every case is a
// rotation, so orientation is preserved.
glm::dvec2 toWorld(const Lot& lot, glm::dvec2 local) {
    const Rect& r = lot.rect;
    switch (lot.front) {
    case Side::South:
        return {r.lo.x + local.x, r.lo.y + local.y};
    case Side::North:
        return {r.hi.x - local.x, r.hi.y - local.y};
    case Side::West:
        return {r.lo.x + local.y, r.hi.y - local.x};
    case Side::East:
        return {r.hi.x - local.y, r.lo.y + local.x};
    }
    return local;
}

} // namespace

void subdivideBlock(const Rect& block, double lotWidth, double lotDepth, uint64_t blockKey,
                    std::vector<Lot>& out) {
    const glm::dvec2 size = block.size();
    Draws draw{combineKey(blockKey, kDepthTag)};
    const double depth = lotDepth * draw.uniform(0.85, 1.15);
    // A courtyard thinner than a third of a lot depth would be a sliver: the strips meet.
    auto stripDepth = [&](double extent) {
        return extent - 2.0 * depth < depth / 3.0 ? 0.5 * extent : depth;
    };
    const double dx = stripDepth(size.x), dy = stripDepth(size.y);

    // South and north strips run the full width and own the corner lots.
    for (const Side side : {Side::South, Side::North}) {
        const double y0 = side == Side::South ? block.lo.y : block.hi.y - dy;
        const uint64_t key = combineKey(blockKey, static_cast<uint64_t>(side));
        auto emit = [&](double a, double b) {
            out.push_back({{{block.lo.x + a, y0}, {block.lo.x + b, y0 + dy}}, side});
        };
        const double middle = size.x - 2.0 * dx;
        if (middle < 0.5 * lotWidth) {
            cutStrip(size.x, lotWidth, key, emit);
        } else {
            emit(0.0, dx);
            cutStrip(middle, lotWidth, key, [&](double a, double b) { emit(dx + a, dx + b); });
            emit(size.x - dx, size.x);
        }
    }
    // West and east strips fill what lies between; a stub shorter than half a lot stays open.
    const double middle = size.y - 2.0 * dy;
    if (middle < 0.5 * lotWidth) return;
    for (const Side side : {Side::West, Side::East}) {
        const double x0 = side == Side::West ? block.lo.x : block.hi.x - dx;
        cutStrip(middle, lotWidth, combineKey(blockKey, static_cast<uint64_t>(side)),
                 [&](double a, double b) {
                     out.push_back({{{x0, block.lo.y + dy + a}, {x0 + dx, block.lo.y + dy + b}}, side});
                 });
    }
}

std::vector<glm::dvec2> makeFootprint(const Lot& lot, uint64_t lotKey) {
    const glm::dvec2 size = lot.rect.size();
    const bool across = lot.front == Side::East || lot.front == Side::West;
    const double frontage = across ? size.y : size.x, depth = across ? size.x : size.y;
    Draws draw{lotKey};
    // Setbacks shrink with small lots, so the footprint stays strictly inside any lot.
    const double side = std::min(0.12 * frontage, draw.uniform(0.8, 2.5));
    const double front = std::min(0.15 * depth, draw.uniform(1.0, 4.0));
    const double back = std::min(0.15 * depth, draw.uniform(1.0, 5.0));
    Polygon shape = drawShape(frontage - 2.0 * side, depth - front - back, draw);
    for (glm::dvec2& p : shape) p = toWorld(lot, p + glm::dvec2(side, front));
    return shape;
}

} // namespace hexlod::scene::detail
