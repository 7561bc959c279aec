#include "hexlod/scene/demo_footprints.h"

#include "footprint_shapes.h"

#include "hexlod/grammar/position_hash.h"

#include <algorithm>
#include <cmath>

namespace hexlod::scene {
namespace {

using grammar::combineKey;
using grammar::unitFloat;

// Deterministic uniform draws for one building: draw k of building b under seed s.
struct Draws {
    uint64_t key;
    uint32_t next = 0;
    float uniform(float lo, float hi) { return lo + (hi - lo) * unitFloat(combineKey(key, next++)); }
};

using detail::Polygon;

Polygon regular(double radius, int sides) {
    Polygon p;
    for (int i = 0; i < sides; ++i) {
        const double angle = 2.0 * M_PI * i / sides;
        p.push_back({radius * std::cos(angle), radius * std::sin(angle)});
    }
    return p;
}

} // namespace

DemoShape demoShapeOf(uint64_t seed, uint32_t building) {
    const uint64_t key = combineKey(combineKey(seed, 0xdead5ull), building);
    return static_cast<DemoShape>(key % static_cast<uint64_t>(DemoShape::count_));
}

std::vector<grammar::BuildingInput> makeDemoFootprints(const DemoOptions& options) {
    std::vector<grammar::BuildingInput> buildings(options.count);
    const uint32_t columns = std::max(1u, static_cast<uint32_t>(std::ceil(std::sqrt(double(options.count)))));
    for (uint32_t id = 0; id < options.count; ++id) {
        Draws draw{combineKey(options.seed, id)};
        const double w = draw.uniform(12.0f, 40.0f), d = draw.uniform(10.0f, 30.0f);
        Polygon polygon;
        double angle = 0.0;
        switch (demoShapeOf(options.seed, id)) {
        case DemoShape::Rectangle:
            polygon = detail::box(w, d);
            break;
        case DemoShape::RotatedRectangle:
            polygon = detail::box(w, d);
            angle = draw.uniform(-0.6f, 0.6f);
            break;
        case DemoShape::LShape:
            polygon = detail::lShape(w, d, draw.uniform(0.35f, 0.6f) * std::min(w, d));
            break;
        case DemoShape::UShape:
            polygon = detail::uShape(w, d, draw.uniform(0.25f, 0.33f) * std::min(w, d));
            break;
        case DemoShape::TShape:
            polygon = detail::tShape(w, d, draw.uniform(0.3f, 0.5f) * w);
            break;
        case DemoShape::Polygon:
            polygon = regular(0.5 * std::min(w, d), 5 + static_cast<int>(draw.uniform(0.0f, 4.0f)));
            angle = draw.uniform(0.0f, 1.0f);
            break;
        case DemoShape::count_:
            break;
        }
        // Centre on the lot, then rotate; footprints stay inside their lot.
        glm::dvec2 lo = polygon[0], hi = polygon[0];
        for (const glm::dvec2& p : polygon) lo = glm::min(lo, p), hi = glm::max(hi, p);
        const glm::dvec2 centre = 0.5 * (lo + hi);
        const glm::dvec2 lot(options.lotSpacing * (id % columns), options.lotSpacing * (id / columns));
        const double c = std::cos(angle), s = std::sin(angle);
        grammar::BuildingInput& b = buildings[id];
        b.id = id;
        for (const glm::dvec2& p : polygon) {
            const glm::dvec2 q = p - centre;
            b.footprint.push_back(lot + glm::dvec2(c * q.x - s * q.y, s * q.x + c * q.y));
        }
    }
    return buildings;
}

std::vector<grammar::ParameterOverride> demoParameterOverrides(const grammar::CompiledGrammar& grammar,
                                                               uint64_t seed, uint32_t building) {
    const int floors = grammar.findParameter("floors");
    if (floors < 0) return {};
    const grammar::ParameterInfo& info = grammar.params[floors];
    const float lo = std::max(info.minValue, info.defaultValue * 0.5f);
    const float hi = std::min(info.maxValue, info.defaultValue * 1.5f);
    Draws draw{combineKey(combineKey(seed, 0xf100ull), building)};
    return {{"floors", std::round(draw.uniform(lo, hi))}};
}

} // namespace hexlod::scene
