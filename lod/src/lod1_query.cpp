// The CPU walk of LOD1's per-pixel grammar.
#include "hexlod/lod/lod1_query.h"
#include "hexlod/grammar/position_hash.h"
#include "hexlod/grammar/subdivision.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <vector>

namespace hexlod::lod {
namespace {

constexpr uint32_t kMarginKeySpace = 0x40000000u; // as the expander numbers Repeat margins
constexpr uint32_t kMaxRepeatTiles = 1u << 20;    // more tiles than any facade holds

struct FaceScope {
    glm::vec2 origin{0.0f}, size{0.0f};
    uint64_t key = 0;
    int32_t floor = 0, floors = 1, index = 0, count = 1;
    uint32_t level = 0, depth = 0;
};

} // namespace

Lod1Hit lod1Query(const grammar::CompiledGrammar& g, const grammar::ExtrudedSet& set, uint32_t buildingIndex,
                  uint32_t elementIndex, glm::vec2 point, uint64_t seed) {
    using namespace grammar;
    const ExtrudedBuilding& building = set.buildings.at(buildingIndex);
    const ExtrudedElement& element = set.elements.at(elementIndex);
    const float* params = set.parameters.data() + building.firstParameter;
    const uint64_t buildingKey = combineKey(combineKey(seed, building.building), 0xb01d1e5ull);
    const glm::vec3 normal = glm::normalize(glm::cross(element.axisX, element.axisY));

    FaceScope s;
    s.size = element.size;
    s.key = element.key;
    s.floor = element.floor, s.floors = element.floors, s.index = element.index, s.count = element.count;
    s.level = element.level, s.depth = element.depth;

    float accessors[kAccessorCount];
    auto argument = [&](const CompiledRule& rule, uint32_t i) {
        const Expression& e = g.expressions[g.arguments[rule.firstArgument + i].expression];
        if (e.isConstant) return e.constantValue;
        const glm::vec3 origin = element.origin + element.axisX * s.origin.x + element.axisY * s.origin.y;
        accessors[int(Accessor::Width)] = s.size.x;
        accessors[int(Accessor::Height)] = s.size.y;
        accessors[int(Accessor::SizeZ)] = 0.0f;
        accessors[int(Accessor::Elevation)] = origin.z - building.baseElevation;
        accessors[int(Accessor::Floor)] = float(s.floor);
        accessors[int(Accessor::Floors)] = float(s.floors);
        accessors[int(Accessor::Index)] = float(s.index);
        accessors[int(Accessor::Count)] = float(s.count);
        accessors[int(Accessor::Level)] = float(s.level);
        accessors[int(Accessor::Depth)] = float(s.depth);
        accessors[int(Accessor::NormalX)] = normal.x;
        accessors[int(Accessor::NormalY)] = normal.y;
        accessors[int(Accessor::NormalZ)] = normal.z;
        accessors[int(Accessor::WorldNormalX)] = normal.x;
        accessors[int(Accessor::WorldNormalY)] = normal.y;
        accessors[int(Accessor::WorldNormalZ)] = normal.z;
        accessors[int(Accessor::Atom)] = float(element.atom);
        accessors[int(Accessor::Atoms)] = float(building.vertexCount);
        accessors[int(Accessor::Building)] = float(building.building);
        return evaluate(&g.code[e.first], e.count,
                        {params, accessors, combineKey(s.key, rule.key + i), buildingKey});
    };
    auto descend = [&](uint64_t slot) {
        s.key = combineKey(s.key, slot);
        ++s.depth;
    };

    Lod1Hit hit;
    uint32_t r = element.rule;
    std::vector<float> sizes, parts;
    for (hit.steps = 0; hit.steps < kLod1MaxSteps; ++hit.steps) {
        hit.rule = r;
        const CompiledRule& rule = g.rules[r];
        auto next = [&](uint32_t i) { return g.successors[rule.firstSuccessor + i]; };
        uint32_t chosen = kNullRule;
        switch (rule.op) {
        case RuleOp::Shape:
            hit.outcome = Lod1Outcome::Terminal;
            hit.shape = rule.shape;
            hit.scopeOrigin = s.origin;
            hit.scopeSize = s.size;
            return hit;
        case RuleOp::Null:
            hit.outcome = Lod1Outcome::Empty;
            return hit;
        case RuleOp::Cond: {
            const bool yes = argument(rule, 0) != 0.0f;
            if (!yes && rule.successorCount < 2) return hit;
            chosen = next(yes ? 0 : 1);
            descend(yes ? 0 : 1);
            break;
        }
        case RuleOp::Choose: {
            float total = 0.0f;
            sizes.resize(rule.argumentCount);
            for (uint32_t i = 0; i < rule.argumentCount; ++i) {
                sizes[i] = argument(rule, i);
                if (!std::isfinite(sizes[i]) || sizes[i] < 0.0f) return hit;
                total += sizes[i];
            }
            if (!(total > 0.0f) || !std::isfinite(total)) return hit;
            const float pick = unitFloat(combineKey(s.key, rule.key)) * total;
            uint32_t i = rule.argumentCount - 1;
            float cumulative = 0.0f;
            for (uint32_t k = 0; k < rule.argumentCount; ++k) {
                cumulative += sizes[k];
                if (pick < cumulative) {
                    i = k;
                    break;
                }
            }
            chosen = next(i);
            descend(i);
            break;
        }
        case RuleOp::Split: {
            if (rule.axis == Axis::Z) {
                hit.outcome = Lod1Outcome::Stopped;
                return hit;
            }
            const int axis = int(rule.axis);
            const uint32_t n = rule.argumentCount;
            sizes.resize(n);
            parts.resize(n);
            bool relative[kMaxSplitParts];
            for (uint32_t i = 0; i < n; ++i) {
                sizes[i] = argument(rule, i);
                relative[i] = g.arguments[rule.firstArgument + i].relative;
            }
            splitSizes(s.size[axis], sizes.data(), relative, n, parts.data());
            // The expander's offsets: the parts' sum, less each part from the last one down.
            float offset = 0.0f;
            for (uint32_t i = 0; i < n; ++i) offset += parts[i];
            const float along = point[axis] - s.origin[axis];
            uint32_t found = n;
            for (uint32_t i = n; i-- > 0;) {
                offset -= parts[i];
                if (parts[i] > 0.0f && along >= offset && along < offset + parts[i]) {
                    found = i;
                    s.origin[axis] += offset;
                    break;
                }
            }
            if (found == n) return hit;
            s.size[axis] = parts[found];
            s.index = int32_t(found), s.count = int32_t(n);
            if (axis == 1) s.floor = s.index, s.floors = s.count;
            chosen = next(found);
            descend(found);
            break;
        }
        case RuleOp::Repeat: {
            if (rule.axis == Axis::Z) {
                hit.outcome = Lod1Outcome::Stopped;
                return hit;
            }
            const int axis = int(rule.axis);
            RepeatLayout layout;
            if (repeatLayout(s.size[axis], argument(rule, 0), rule.mode, kMaxRepeatTiles, layout) !=
                SubdivisionStatus::Ok) {
                return hit;
            }
            const float along = point[axis] - s.origin[axis];
            const float tilesEnd = layout.margin + float(layout.tiles) * layout.tileSize;
            if (along >= layout.margin && along < tilesEnd && layout.tiles > 0) {
                const uint32_t i =
                    std::min(uint32_t((along - layout.margin) / layout.tileSize), layout.tiles - 1);
                s.origin[axis] += layout.margin + float(i) * layout.tileSize;
                s.size[axis] = layout.tileSize;
                s.index = int32_t(i), s.count = int32_t(layout.tiles);
                if (axis == 1) s.floor = s.index, s.floors = s.count;
                chosen = next(0);
                descend(i);
            } else if (rule.successorCount == 2 && layout.margin > 0.0f) {
                const uint32_t j = along < layout.margin ? 0 : 1;
                s.origin[axis] += j == 0 ? 0.0f : tilesEnd;
                s.size[axis] = j == 0 ? layout.margin : std::max(0.0f, s.size[axis] - tilesEnd);
                s.index = int32_t(j), s.count = 2;
                chosen = next(1);
                descend(kMarginKeySpace + j);
            } else {
                return hit;
            }
            break;
        }
        default:
            hit.outcome = Lod1Outcome::Stopped;
            return hit;
        }
        if (chosen == kNullRule) return hit;
        r = chosen;
    }
    hit.outcome = Lod1Outcome::Stopped;
    return hit;
}

} // namespace hexlod::lod
