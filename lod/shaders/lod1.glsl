// LOD1's per-pixel grammar interpreter (Marvie et al. 2011, algorithm 1): the steps of
// lod1_query.cpp over the tables lod1_codegen.cpp generates into "lod1_grammar.glsl". Random
// picks use the expander's 64-bit position keys (GL_ARB_gpu_shader_int64), and Split and
// Repeat sizes the same double arithmetic as grammar/subdivision.cpp, so LOD1 picks the
// terminals the terminal set holds.
struct Lod1Scope {
    vec2 origin, size; // in the element's face coordinates, metres
    uint64_t key;
    int floor, floors, index, count;
    uint level, depth;
};

struct Lod1Context {
    vec3 origin, axisX, axisY, normal; // the element, cell-local
    float baseZ;
    uint atom, atoms, building, parameters;
    uint64_t buildingKey;
};

layout(std430, binding = 11) readonly buffer Lod1ParameterBuffer { float lod1Params[]; };

uint64_t lod1Mix(uint64_t x) {
    x += 0x9e3779b97f4a7c15ul;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ul;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebul;
    return x ^ (x >> 31);
}
uint64_t lod1Combine(uint64_t key, uint64_t value) { return lod1Mix(key ^ lod1Mix(value)); }
float lod1Unit(uint64_t key) { return float(uint(key >> 40)) * (1.0 / 16777216.0); }
float lod1Fmod(float a, float b) { return a - b * trunc(a / b); }

#include "lod1_grammar.glsl"

#define LOD1_TERMINAL 0u
#define LOD1_EMPTY 1u
#define LOD1_STOPPED 2u
#define LOD1_MAX_STEPS 64

struct Lod1Hit {
    uint outcome, shape;
    vec2 origin, size;
};

float lod1Arg(uint rule, uint i, Lod1Scope s, Lod1Context c) {
    return lod1Argument(lod1RuleArguments[rule] + i, s, c, lod1Combine(s.key, lod1RuleKey[rule] + uint64_t(i)));
}

Lod1Scope lod1Descend(Lod1Scope s, uint64_t slot) {
    s.key = lod1Combine(s.key, slot);
    s.depth += 1u;
    return s;
}

Lod1Hit lod1Walk(uint rule, Lod1Scope s, Lod1Context c, vec2 point) {
    Lod1Hit hit = Lod1Hit(LOD1_EMPTY, 0u, vec2(0.0), vec2(0.0));
    for (int step = 0; step < LOD1_MAX_STEPS; ++step) {
        uint word = lod1RuleOp[rule];
        uint op = word & 0xffu, axis = (word >> 8) & 0xfu, mode = (word >> 12) & 0xfu;
        uint successors = lod1RuleSuccessors[rule], successorCount = lod1RuleSuccessorCount[rule];
        uint arguments = lod1RuleArgumentCount[rule];
        uint chosen = 0xffffffffu;
        // llvmpipe runs every branch for every pixel (masked, not branched around), and each
        // argument evaluation runs every case of lod1Argument, so each argument is evaluated
        // once, into values[], and only for the ops the walk takes; the passes over them after
        // are plain reads. The first: Cond's and Repeat's value, Choose's total, Split's sums.
        bool split = op == 1u && axis < 2u, choose = op == 10u;
        bool walked = split || choose || op == 6u || (op == 2u && axis < 2u);
        float values[LOD1_MAX_ARGUMENTS];
        float first = 0.0, total = 0.0;
        bool valid = true;
        double absoluteSum = 0.0, relativeSum = 0.0;
        for (uint i = 0u; i < (walked ? arguments : 0u); ++i) {
            float value = lod1Arg(rule, i, s, c);
            values[i] = value;
            if (i == 0u) first = value;
            bool finite = !(isnan(value) || isinf(value) || value < 0.0);
            valid = valid && finite;
            total += finite ? value : 0.0;
            double size = finite ? double(value) : 0.0;
            if (lod1ArgumentRelative[lod1RuleArguments[rule] + i] != 0u) relativeSum += size;
            else absoluteSum += size;
        }
        // The second: Choose's pick; Split's parts and offsets as the expander lays them out,
        // the sum, then (third pass) less each part from the end.
        float pick = lod1Unit(lod1Combine(s.key, lod1RuleKey[rule])) * total;
        double available = max(0.0, double(s.size[min(axis, 1u)]));
        double remainder = available - absoluteSum;
        double absoluteScale = remainder < 0.0 ? available / absoluteSum : 1.0;
        double relativeScale = (remainder > 0.0 && relativeSum > 0.0) ? remainder / relativeSum : 0.0;
        float offset = 0.0, cumulative = 0.0;
        uint picked = arguments - 1u;
        for (uint i = 0u; i < (split || (choose && valid) ? arguments : 0u); ++i) {
            float value = values[i];
            cumulative += value;
            if (choose && pick < cumulative) {
                picked = i;
                break;
            }
            if (isnan(value) || isinf(value) || value < 0.0) value = 0.0;
            bool relative = lod1ArgumentRelative[lod1RuleArguments[rule] + i] != 0u;
            offset += float(double(value) * (relative ? relativeScale : absoluteScale));
        }
        uint found = arguments;
        float part = 0.0;
        float along = point[min(axis, 1u)] - s.origin[min(axis, 1u)];
        for (uint k = split ? arguments : 0u; k-- > 0u;) {
            float size = values[k];
            if (isnan(size) || isinf(size) || size < 0.0) size = 0.0;
            bool relative = lod1ArgumentRelative[lod1RuleArguments[rule] + k] != 0u;
            part = float(double(size) * (relative ? relativeScale : absoluteScale));
            offset -= part;
            if (part > 0.0 && along >= offset && along < offset + part) {
                found = k;
                break;
            }
        }
        if (op == 7u) { // Shape
            return Lod1Hit(LOD1_TERMINAL, lod1RuleShape[rule], s.origin, s.size);
        } else if (op == 11u) { // NULL
            return hit;
        } else if (op == 6u) { // Cond
            bool yes = first != 0.0;
            if (!yes && successorCount < 2u) return hit;
            chosen = lod1Successors[successors + (yes ? 0u : 1u)];
            s = lod1Descend(s, yes ? 0ul : 1ul);
        } else if (choose) {
            if (!valid || !(total > 0.0) || isinf(total)) return hit;
            chosen = lod1Successors[successors + picked];
            s = lod1Descend(s, uint64_t(picked));
        } else if (split) { // along x or y
            if (found == arguments) return hit;
            s.origin[axis] += offset;
            s.size[axis] = part;
            s.index = int(found);
            s.count = int(arguments);
            if (axis == 1u) {
                s.floor = s.index;
                s.floors = s.count;
            }
            chosen = lod1Successors[successors + found];
            s = lod1Descend(s, uint64_t(found));
        } else if (op == 2u && axis < 2u) { // Repeat along x or y
            float tile = first;
            float length = s.size[axis];
            if (isnan(tile) || isinf(tile) || !(tile > 0.0) || !(length > 0.0)) return hit;
            double ratio = double(length) / double(tile);
            double tiles = mode == 0u ? floor(ratio + 1e-5) : max(1.0, roundEven(ratio));
            if (tiles > 1048576.0) return hit;
            float tileSize = mode == 0u ? tile : float(double(length) / tiles);
            float margin = mode == 0u ? float(max(0.0, 0.5 * (double(length) - tiles * double(tile)))) : 0.0;
            uint count = uint(tiles);
            float along = point[axis] - s.origin[axis];
            float tilesEnd = margin + float(count) * tileSize;
            if (count > 0u && along >= margin && along < tilesEnd) {
                uint i = min(uint((along - margin) / tileSize), count - 1u);
                s.origin[axis] += margin + float(i) * tileSize;
                s.size[axis] = tileSize;
                s.index = int(i);
                s.count = int(count);
                if (axis == 1u) {
                    s.floor = s.index;
                    s.floors = s.count;
                }
                chosen = lod1Successors[successors];
                s = lod1Descend(s, uint64_t(i));
            } else if (successorCount == 2u && margin > 0.0) {
                uint j = along < margin ? 0u : 1u;
                s.origin[axis] += j == 0u ? 0.0 : tilesEnd;
                s.size[axis] = j == 0u ? margin : max(0.0, s.size[axis] - tilesEnd);
                s.index = int(j);
                s.count = 2;
                chosen = lod1Successors[successors + 1u];
                s = lod1Descend(s, 0x40000000ul + uint64_t(j));
            } else {
                return hit;
            }
        } else {
            hit.outcome = LOD1_STOPPED;
            return hit;
        }
        if (chosen == 0xffffffffu) return hit;
        rule = chosen;
        // A successor that ends the walk ends it here, not in an iteration of its own: llvmpipe
        // runs the whole body for a pixel until every pixel of its group has left the loop.
        // Within the step limit only, where lod1Query's walk would reach it.
        uint next = step + 1 < LOD1_MAX_STEPS ? lod1RuleOp[rule] & 0xffu : 0u;
        if (next == 7u) return Lod1Hit(LOD1_TERMINAL, lod1RuleShape[rule], s.origin, s.size); // Shape
        if (next == 11u) return hit;                                                         // NULL
    }
    hit.outcome = LOD1_STOPPED;
    return hit;
}
