// Segment-based expansion (Buron 2014, thesis §4.4.2): each footprint edge is a 1D atom;
// Extrude turns an atom into a facade face plus the translated atom, and the remaining
// rules of thesis Appendix A subdivide, move or pick among scopes until Shape emits a
// terminal. Expansion is depth-first over an explicit stack so that depth and work caps
// are checked per scope and nothing recurses on the C++ stack.
#include "hexlod/grammar/expander.h"

#include "hexlod/grammar/footprint.h"
#include "hexlod/grammar/position_hash.h"
#include "hexlod/grammar/subdivision.h"
#include "scope.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>

namespace hexlod::grammar {

namespace {
struct WorkItem {
    Scope scope;
    uint32_t rule;
    bool belowStop; // already past an extruded-set stop on this path
};
constexpr float kDegrees = 3.14159265358979323846f / 180.0f;
constexpr uint32_t kMarginKeySpace = 0x40000000u;
constexpr uint32_t kMaxBranch = 1024;

bool finite3(float a, float b, float c) {
    return std::isfinite(a) && std::isfinite(b) && std::isfinite(c);
}
} // namespace

struct BuildingExpander::Impl {
    const CompiledGrammar& grammar;
    ExpansionSettings settings;
    std::vector<WorkItem> stack;
    std::vector<float> sizes, parts;
    // Terminals of the building being expanded. It keeps its capacity across buildings and
    // is copied out once at its final size: growing a fresh vector per building crossed
    // malloc's mmap threshold and spent a third of the time clearing new pages.
    std::vector<TerminalRecord> terminals;

    // Per building and per atom state.
    BuildingOutput* out = nullptr;
    const float* params = nullptr;
    uint32_t building = 0;
    uint64_t buildingKey = 0;
    uint32_t atom = 0, atomCount = 0;
    float baseZ = 0.0f;
    glm::vec3 worldNormal{0.0f};
    uint32_t atomTerminals = 0, atomOperations = 0;
    bool atomAborted = false;
    float accessors[kAccessorCount] = {};
    const Scope* accessorScope = nullptr;

    Impl(const CompiledGrammar& g, const ExpansionSettings& s) : grammar(g), settings(s) {}

    void issue(IssueKind kind, uint32_t rule, std::string detail = {}) {
        for (ExpansionIssue& existing : out->issues) {
            if (existing.kind == kind && existing.rule == rule) return; // one report per building and rule
        }
        out->issues.push_back({kind, rule, building, std::move(detail)});
    }

    void fillAccessors(const Scope& s) {
        float* a = accessors;
        a[int(Accessor::Width)] = s.size.x;
        a[int(Accessor::Height)] = s.size.y;
        a[int(Accessor::SizeZ)] = s.size.z;
        a[int(Accessor::Elevation)] = s.origin.z - baseZ;
        a[int(Accessor::Floor)] = float(s.floor);
        a[int(Accessor::Floors)] = float(s.floors);
        a[int(Accessor::Index)] = float(s.index);
        a[int(Accessor::Count)] = float(s.count);
        a[int(Accessor::Level)] = float(s.level);
        a[int(Accessor::Depth)] = float(s.depth);
        a[int(Accessor::NormalX)] = s.z.x;
        a[int(Accessor::NormalY)] = s.z.y;
        a[int(Accessor::NormalZ)] = s.z.z;
        a[int(Accessor::WorldNormalX)] = worldNormal.x;
        a[int(Accessor::WorldNormalY)] = worldNormal.y;
        a[int(Accessor::WorldNormalZ)] = worldNormal.z;
        a[int(Accessor::Atom)] = float(atom);
        a[int(Accessor::Atoms)] = float(atomCount);
        a[int(Accessor::Building)] = float(building);
        accessorScope = &s;
    }

    float argument(const CompiledRule& rule, uint32_t i, const Scope& s) {
        const Expression& e = grammar.expressions[grammar.arguments[rule.firstArgument + i].expression];
        if (e.isConstant) return e.constantValue;
        if (accessorScope != &s) fillAccessors(s);
        return evaluate(&grammar.code[e.first], e.count,
                        {params, accessors, combineKey(s.key, rule.key + i), buildingKey});
    }

    uint32_t successor(const CompiledRule& rule, uint32_t i) const {
        return grammar.successors[rule.firstSuccessor + i];
    }

    // Pushes a copy of `parent` for `rule` and returns it for the caller to adjust, or null
    // when the successor is NULL or the depth cap is reached. Building the child in place
    // on the stack saves a scope copy per rule application, the hot path here. The pointer
    // is valid until the next spawn.
    Scope* spawn(const Scope& parent, uint64_t slot, uint32_t rule, bool belowStop, uint32_t parentRule) {
        if (rule == kNullRule) return nullptr;
        if (stack.size() >= settings.limits.maxPendingScopes) {
            issue(IssueKind::AtomOperationCap, parentRule,
                  "more than " + std::to_string(settings.limits.maxPendingScopes) +
                      " scopes waiting on atom " + std::to_string(atom));
            atomAborted = true;
            return nullptr;
        }
        if (parent.depth >= settings.limits.maxDepth) {
            issue(IssueKind::DepthCap, parentRule, "depth " + std::to_string(parent.depth + 1));
            return nullptr;
        }
        WorkItem& item = stack.emplace_back(WorkItem{parent, rule, belowStop});
        item.scope.key = combineKey(parent.key, slot);
        item.scope.depth = static_cast<uint16_t>(parent.depth + 1);
        return &item.scope;
    }

    void recordElement(const Scope& s, uint32_t rule) {
        out->elements.push_back({s.origin, s.x, s.y, glm::vec2(s.size.x, s.size.y), rule, atom, s.key,
                                 s.floor, s.floors, s.index, s.count, s.level, s.depth});
        const float top = std::max(s.origin.z, s.origin.z + s.y.z * s.size.y) - baseZ;
        out->height = std::max(out->height, top);
    }

    void emit(const Scope& s, const CompiledRule& rule, uint32_t ruleIndex) {
        if (++atomTerminals > settings.limits.maxTerminalsPerAtom) {
            issue(IssueKind::AtomTerminalCap, ruleIndex,
                  "more than " + std::to_string(settings.limits.maxTerminalsPerAtom) + " terminals on atom " +
                      std::to_string(atom));
            atomAborted = true;
            return;
        }
        float ratio = grammar.shapes[rule.shape].depthRatio;
        if (rule.argumentCount > 0) {
            const float given = argument(rule, 0, s);
            if (std::isfinite(given) && given >= 0.0f) {
                ratio = given;
            } else {
                issue(IssueKind::InvalidSize, ruleIndex, "depth ratio; the shape's default was used");
            }
        }
        terminals.push_back(packTerminal(s.origin, s.x, s.y, s.z, glm::vec2(s.size.x, s.size.y), ratio,
                                         rule.shape, building));
    }

    void extrude(const Scope& s, const CompiledRule& rule, uint32_t r, bool below) {
        const float height = argument(rule, 0, s);
        const float scale = rule.argumentCount > 1 ? argument(rule, 1, s) : 1.0f;
        const float twist = rule.argumentCount > 2 ? argument(rule, 2, s) : 0.0f;
        if (!finite3(height, scale, twist) || height < 0.0f || scale < 0.0f) {
            return issue(IssueKind::InvalidSize, r, "Extrude height or scale; the scope was dropped");
        }
        if (s.dimension == 3) return issue(IssueKind::WrongScopeKind, r, "Extrude needs an atom or a face");
        // An atom grows along its up axis into a face; a face grows along its normal into a box.
        const glm::vec3 growth = s.dimension == 1 ? s.y : s.z;
        if (Scope* top = spawn(s, 1, successor(rule, 1), below, r)) {
            if (twist != 0.0f) {
                const glm::quat spin = glm::angleAxis(twist * kDegrees, growth);
                top->x = glm::normalize(spin * s.x);
                top->y = glm::normalize(spin * s.y);
                top->z = glm::normalize(spin * s.z);
            }
            top->size.x = s.size.x * scale;
            if (s.dimension == 2) top->size.y = s.size.y * scale;
            const glm::vec3 center = s.center() + growth * height;
            top->origin = center - top->x * (0.5f * top->size.x) - top->y * (0.5f * top->size.y) -
                          top->z * (0.5f * top->size.z);
        }
        if (Scope* side = spawn(s, 0, successor(rule, 0), below, r)) {
            side->dimension = static_cast<uint8_t>(s.dimension + 1);
            (s.dimension == 1 ? side->size.y : side->size.z) = height;
        }
    }

    void split(const Scope& s, const CompiledRule& rule, uint32_t r, bool below) {
        const uint32_t n = rule.argumentCount;
        sizes.resize(n);
        parts.resize(n);
        bool relative[kMaxSplitParts];
        for (uint32_t i = 0; i < n; ++i) {
            sizes[i] = argument(rule, i, s);
            relative[i] = grammar.arguments[rule.firstArgument + i].relative;
        }
        const int axis = static_cast<int>(rule.axis);
        if (splitSizes(s.size[axis], sizes.data(), relative, n, parts.data()) != SubdivisionStatus::Ok) {
            issue(IssueKind::InvalidSize, r, "Split size; treated as 0");
        }
        float offset = 0.0f;
        for (uint32_t i = 0; i < n; ++i) offset += parts[i];
        const glm::vec3 direction = s.axis(axis);
        for (uint32_t i = n; i-- > 0;) {
            offset -= parts[i];
            if (!(parts[i] > 0.0f)) continue;
            if (Scope* child = spawn(s, i, successor(rule, i), below, r)) {
                child->origin = s.origin + direction * offset;
                child->size[axis] = parts[i];
                child->index = static_cast<int32_t>(i);
                child->count = static_cast<int32_t>(n);
                if (axis == 1) child->floor = child->index, child->floors = child->count;
            }
        }
    }

    void repeat(const Scope& s, const CompiledRule& rule, uint32_t r, bool below) {
        const int axis = static_cast<int>(rule.axis);
        // Tiles count against both the work left and the room left on the stack, so a tile
        // size tending to 0 is refused up front instead of allocating gigabytes.
        const ExpansionLimits& limits = settings.limits;
        const uint32_t budget = std::min(
            limits.maxOperationsPerAtom - std::min(atomOperations, limits.maxOperationsPerAtom),
            limits.maxPendingScopes - std::min(static_cast<uint32_t>(stack.size()), limits.maxPendingScopes));
        RepeatLayout layout;
        const SubdivisionStatus status =
            repeatLayout(s.size[axis], argument(rule, 0, s), rule.mode, budget, layout);
        if (status == SubdivisionStatus::InvalidSize)
            return issue(IssueKind::InvalidSize, r, "Repeat tile size; the scope was dropped");
        if (status == SubdivisionStatus::TooManyTiles) return issue(IssueKind::TooManyTiles, r);
        const glm::vec3 direction = s.axis(axis);
        if (rule.successorCount == 2 && layout.margin > 0.0f) {
            const float after = layout.margin + layout.tiles * layout.tileSize;
            for (uint32_t j = 2; j-- > 0;) {
                if (Scope* margin = spawn(s, kMarginKeySpace + j, successor(rule, 1), below, r)) {
                    margin->origin = s.origin + direction * (j == 0 ? 0.0f : after);
                    margin->size[axis] = j == 0 ? layout.margin : std::max(0.0f, s.size[axis] - after);
                    margin->index = static_cast<int32_t>(j);
                    margin->count = 2;
                }
            }
        }
        for (uint32_t i = layout.tiles; i-- > 0;) {
            if (Scope* tile = spawn(s, i, successor(rule, 0), below, r)) {
                tile->origin =
                    s.origin + direction * (layout.margin + static_cast<float>(i) * layout.tileSize);
                tile->size[axis] = layout.tileSize;
                tile->index = static_cast<int32_t>(i);
                tile->count = static_cast<int32_t>(layout.tiles);
                if (axis == 1) tile->floor = tile->index, tile->floors = tile->count;
            }
        }
    }

    void branch(const Scope& s, const CompiledRule& rule, uint32_t r, bool below) {
        const float count = argument(rule, 0, s);
        if (!std::isfinite(count) || count < 0.0f || count > float(kMaxBranch)) {
            return issue(IssueKind::InvalidCount, r, "Branch count");
        }
        const uint32_t n = static_cast<uint32_t>(std::nearbyint(count));
        for (uint32_t i = n; i-- > 0;) {
            const uint32_t next =
                successor(rule, rule.successorCount == 1 ? 0 : std::min(i, rule.successorCount - 1));
            if (Scope* copy = spawn(s, i, next, below, r)) {
                copy->level = static_cast<uint16_t>(s.level + 1);
                copy->index = static_cast<int32_t>(i);
                copy->count = static_cast<int32_t>(n);
            }
        }
    }

    void translate(const Scope& s, const CompiledRule& rule, uint32_t r, bool below) {
        const float tx = argument(rule, 0, s), ty = argument(rule, 1, s), tz = argument(rule, 2, s);
        if (!finite3(tx, ty, tz)) return issue(IssueKind::InvalidTransform, r, "Translate");
        if (Scope* moved = spawn(s, 0, successor(rule, 0), below, r))
            moved->origin += s.x * tx + s.y * ty + s.z * tz;
    }

    void rotate(const Scope& s, const CompiledRule& rule, uint32_t r, bool below) {
        const float degrees = argument(rule, 0, s);
        if (!std::isfinite(degrees)) return issue(IssueKind::InvalidTransform, r, "Rotate");
        const glm::quat turn = glm::angleAxis(degrees * kDegrees, s.axis(static_cast<int>(rule.axis)));
        const glm::vec3 pivot = rule.pivot == Pivot::Center ? s.center() : s.origin;
        if (Scope* turned = spawn(s, 0, successor(rule, 0), below, r)) {
            turned->x = glm::normalize(turn * s.x);
            turned->y = glm::normalize(turn * s.y);
            turned->z = glm::normalize(turn * s.z);
            turned->origin = pivot + turn * (s.origin - pivot);
        }
    }

    void choose(const Scope& s, const CompiledRule& rule, uint32_t r, bool below) {
        float total = 0.0f;
        sizes.resize(rule.argumentCount);
        for (uint32_t i = 0; i < rule.argumentCount; ++i) {
            sizes[i] = argument(rule, i, s);
            if (!std::isfinite(sizes[i]) || sizes[i] < 0.0f) return issue(IssueKind::InvalidProbability, r);
            total += sizes[i];
        }
        if (!(total > 0.0f) || !std::isfinite(total)) return issue(IssueKind::InvalidProbability, r);
        // The pick hashes the scope's position key with the rule, never a running counter.
        const float pick = unitFloat(combineKey(s.key, rule.key)) * total;
        uint32_t chosen = rule.argumentCount - 1;
        float cumulative = 0.0f;
        for (uint32_t i = 0; i < rule.argumentCount; ++i) {
            cumulative += sizes[i];
            if (pick < cumulative) {
                chosen = i;
                break;
            }
        }
        spawn(s, chosen, successor(rule, chosen), below, r);
    }

    void explode(const Scope& s, const CompiledRule& rule, uint32_t r, bool below) {
        if (s.dimension == 1) return issue(IssueKind::WrongScopeKind, r, "Explode needs a face or a volume");
        const glm::vec3 sz = s.size;
        struct Face {
            glm::vec3 origin, x, y;
            glm::vec2 size;
        };
        // left, front, right, back, top ("face"); each face's normal points out of the box.
        const Face faces[5] = {
            {s.origin, s.z, s.y, {sz.z, sz.y}},
            {s.origin + s.z * sz.z, s.x, s.y, {sz.x, sz.y}},
            {s.origin + s.x * sz.x + s.z * sz.z, -s.z, s.y, {sz.z, sz.y}},
            {s.origin + s.x * sz.x, -s.x, s.y, {sz.x, sz.y}},
            {s.origin + s.y * sz.y + s.z * sz.z, s.x, -s.z, {sz.x, sz.z}},
        };
        for (uint32_t i = 5; i-- > 0;) {
            if (!(faces[i].size.x > 0.0f && faces[i].size.y > 0.0f)) continue;
            if (Scope* face = spawn(s, i, successor(rule, i), below, r)) {
                face->origin = faces[i].origin;
                face->x = faces[i].x;
                face->y = faces[i].y;
                face->z = glm::cross(face->x, face->y);
                face->size = glm::vec3(faces[i].size, 0.0f);
                face->dimension = 2;
                face->index = static_cast<int32_t>(i);
                face->count = 5;
            }
        }
    }

    void project(const Scope& s, const CompiledRule& rule, uint32_t r, bool below) {
        const int a = static_cast<int>(rule.axis), b = static_cast<int>(rule.secondAxis), c = 3 - a - b;
        if (Scope* projected = spawn(s, 0, successor(rule, 0), below, r)) {
            projected->x = s.axis(a);
            projected->y = s.axis(b);
            projected->z = glm::cross(projected->x, projected->y);
            projected->size = glm::vec3(s.size[a], s.size[b], s.size[c]);
        }
    }

    void apply(WorkItem& item) {
        const uint32_t r = item.rule;
        const CompiledRule& rule = grammar.rules[r];
        if (rule.extrudedStop && !item.belowStop) {
            recordElement(item.scope, r);
            if (settings.extrudedOnly) return;
            item.belowStop = true;
        }
        const Scope& s = item.scope;
        const bool below = item.belowStop;
        switch (rule.op) {
        case RuleOp::Extrude:
            return extrude(s, rule, r, below);
        case RuleOp::Split:
            return split(s, rule, r, below);
        case RuleOp::Repeat:
            return repeat(s, rule, r, below);
        case RuleOp::Branch:
            return branch(s, rule, r, below);
        case RuleOp::Translate:
            return translate(s, rule, r, below);
        case RuleOp::Rotate:
            return rotate(s, rule, r, below);
        case RuleOp::Cond: {
            const bool yes = argument(rule, 0, s) != 0.0f;
            if (yes || rule.successorCount == 2)
                spawn(s, yes ? 0 : 1, successor(rule, yes ? 0 : 1), below, r);
            return;
        }
        case RuleOp::Shape:
            return emit(s, rule, r);
        case RuleOp::Explode:
            return explode(s, rule, r, below);
        case RuleOp::Project:
            return project(s, rule, r, below);
        case RuleOp::Choose:
            return choose(s, rule, r, below);
        case RuleOp::Null:
            return;
        }
    }

    void expandAtom(const glm::vec3& p0, const glm::vec3& p1) {
        Scope s;
        const glm::vec3 edge = p1 - p0;
        s.origin = p0;
        s.x = glm::normalize(edge);
        s.y = glm::vec3(0, 0, 1);
        s.z = glm::cross(s.x, s.y); // outward for a counter-clockwise footprint
        s.size = glm::vec3(glm::length(edge), 0.0f, 0.0f);
        s.key = combineKey(combineKey(settings.seed, building), atom);
        s.index = static_cast<int32_t>(atom);
        s.count = static_cast<int32_t>(atomCount);
        worldNormal = s.z;

        const size_t terminalStart = terminals.size(), elementStart = out->elements.size();
        atomTerminals = atomOperations = 0;
        atomAborted = false;
        stack.clear();
        stack.push_back({s, grammar.axiom, false});
        while (!stack.empty() && !atomAborted) {
            WorkItem item = stack.back();
            stack.pop_back();
            accessorScope = nullptr;
            if (++atomOperations > settings.limits.maxOperationsPerAtom) {
                issue(IssueKind::AtomOperationCap, item.rule,
                      "more than " + std::to_string(settings.limits.maxOperationsPerAtom) +
                          " rule applications on atom " + std::to_string(atom));
                atomAborted = true;
                break;
            }
            apply(item);
        }
        if (atomAborted) {
            // An atom is either whole or absent: a half-built facade would be a silent wrong result.
            terminals.resize(terminalStart);
            out->elements.resize(elementStart);
            stack.clear();
        }
    }

    void expand(const BuildingInput& input, BuildingOutput& output, TerminalArena* arena) {
        out = &output;
        output = BuildingOutput{};
        terminals.clear();
        building = input.id;
        buildingKey = combineKey(combineKey(settings.seed, building), 0xb01d1e5ull);
        params = input.parameters.data();
        std::vector<float> defaults;
        if (input.parameters.size() != grammar.params.size()) {
            if (!input.parameters.empty()) issue(IssueKind::BadParameters, kNullRule);
            defaults = grammar.defaultParameters();
            params = defaults.data();
        }
        std::vector<glm::dvec2> local;
        local.reserve(input.footprint.size());
        for (const glm::dvec2& p : input.footprint) local.push_back(p - glm::dvec2(settings.cellOrigin));
        CleanFootprint clean;
        std::string why;
        if (!cleanFootprint(local, clean, why)) {
            issue(IssueKind::DegenerateFootprint, kNullRule, why);
            output.skipped = true;
            return;
        }
        if (clean.selfIntersecting) issue(IssueKind::SelfIntersectingFootprint, kNullRule);
        baseZ = static_cast<float>(input.baseElevation - settings.cellOrigin.z);
        output.baseElevation = baseZ;
        atomCount = static_cast<uint32_t>(clean.points.size());
        output.atoms = atomCount;
        output.footprint.reserve(atomCount);
        for (const glm::dvec2& p : clean.points) output.footprint.emplace_back(p);
        for (atom = 0; atom < atomCount; ++atom) {
            const glm::dvec2 a = clean.points[atom], b = clean.points[(atom + 1) % atomCount];
            expandAtom(glm::vec3(glm::vec2(a), baseZ), glm::vec3(glm::vec2(b), baseZ));
        }
        if (arena) {
            output.arenaTerminals = arena->append(terminals);
        } else {
            output.terminals.assign(terminals.begin(), terminals.end());
        }
    }
};

BuildingExpander::BuildingExpander(const CompiledGrammar& grammar, const ExpansionSettings& settings)
    : impl_(new Impl(grammar, settings)) {}
BuildingExpander::~BuildingExpander() {
    delete impl_;
}

void BuildingExpander::expand(const BuildingInput& building, BuildingOutput& out) {
    impl_->expand(building, out, nullptr);
}

void BuildingExpander::expand(const BuildingInput& building, BuildingOutput& out, TerminalArena& arena) {
    impl_->expand(building, out, &arena);
}

std::span<const TerminalRecord> TerminalArena::append(std::span<const TerminalRecord> records) {
    if (records.empty()) return {};
    if (blocks_.empty() || blocks_.back().capacity() - blocks_.back().size() < records.size()) {
        blocks_.emplace_back().reserve(std::max(kBlockRecords, records.size()));
    }
    TerminalBuffer& block = blocks_.back();
    const size_t first = block.size();
    block.insert(block.end(), records.begin(), records.end()); // within capacity: no reallocation
    return {block.data() + first, records.size()};
}

} // namespace hexlod::grammar
