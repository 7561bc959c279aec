// Tree parts of the growth grammar (configs/grammars/tree.grammar, thesis §4.6.2). A limb's
// scope is the face an Extrude grows over the limb's base edge: x across the limb, y along
// its growth, z out of the face. Bark and twigs are therefore cylinders centred in x and on
// the face plane (t = 0), as the segments of one limb stack end to end; leaves lie in the face,
// their stalk at y = 0; fruit fills its scope.
#include "shape_generators.h"

#include <algorithm>

namespace hexlod::render {
namespace {

// Round in metric space at the nominal size (width = depth), centred on the face plane.
void limb(MeshBuilder& b, int segments, int rings, float taper, float bumps, uint32_t rgba, bool tip) {
    const float W = b.W(), H = b.H(), D = b.D();
    const float radius = 0.5f * std::min(W, D) / (1.0f + bumps);
    b.frustum({0.5f * W, 0, 0}, {0.5f * W, H, 0}, radius, radius * taper, segments, rings, rgba, false, tip,
              [&](int ring, int segment) {
                  // Ridges of bark along the limb; the end rings stay round so segments meet.
                  if (ring == 0 || ring == rings) return 1.0f;
                  return 1.0f + bumps * (2.0f * detailJitter(uint32_t(ring), uint32_t(segment)) - 1.0f);
              });
}

void bark(MeshBuilder& b, int detail) {
    limb(b, 4 + detail, 2 + detail / 4, 0.95f, 0.06f, palette::kBark, false);
}

void twig(MeshBuilder& b, int detail) {
    limb(b, 3 + detail / 2, 2 + detail / 3, 0.6f, 0.0f, palette::kBark, true);
}

// A pointed leaf folded along its midrib and curling up towards the tip, double-sided.
void leaf(MeshBuilder& b, int detail) {
    const float W = b.W(), H = b.H(), D = b.D();
    const int sections = 2 + detail;
    const float stalk = 0.08f * H, cx = 0.5f * W;
    const auto curl = [&](float f) { return D * (0.1f + 0.4f * f * f); };
    std::vector<glm::vec3> left, mid, right;
    for (int i = 1; i < sections; ++i) {
        const float f = float(i) / float(sections), y = stalk + (H - stalk) * f;
        const float half = 0.5f * W * std::sin(3.14159265f * std::pow(f, 0.8f));
        mid.push_back({cx, y, curl(f) - 0.1f * D});
        left.push_back({cx - half, y, curl(f) + 0.4f * D});
        right.push_back({cx + half, y, curl(f) + 0.4f * D});
    }
    const glm::vec3 base(cx, stalk, curl(0.0f) - 0.1f * D), tip(cx, H, curl(1.0f));
    const auto both = [&](const glm::vec3& a, const glm::vec3& c, const glm::vec3& d) {
        const glm::vec3 tri[3] = {a, c, d};
        const glm::vec3 up = glm::cross(c - a, d - a);
        const glm::vec3 front = up.z >= 0.0f ? up : -up;
        b.polygon(tri, front, palette::kLeaf);
        b.polygon(tri, -front, palette::kLeafBack);
    };
    for (size_t i = 0; i < mid.size(); ++i) {
        if (i == 0) {
            both(base, mid[0], left[0]);
            both(base, right[0], mid[0]);
            continue;
        }
        both(mid[i - 1], mid[i], left[i]);
        both(mid[i - 1], left[i], left[i - 1]);
        both(mid[i - 1], right[i - 1], right[i]);
        both(mid[i - 1], right[i], mid[i]);
    }
    both(mid.back(), tip, left.back());
    both(mid.back(), right.back(), tip);
    b.twoSidedQuad({cx - 0.01f * W, 0, 0}, {cx + 0.01f * W, 0, 0}, {cx + 0.01f * W, stalk, base.z},
                   {cx - 0.01f * W, stalk, base.z}, {0, 0, 1}, palette::kLeafBack, palette::kLeafBack);
}

void fruit(MeshBuilder& b, int detail) {
    const glm::vec3 size(b.W(), b.H(), b.D());
    b.sphere(glm::vec3(0.5f * size.x, 0.5f * size.y, 0.0f), 0.48f * size, 4 + detail, 3 + 3 * detail / 4,
             palette::kFruit);
}

// A tree part drawn coarse is a few pixels across, and the parts are most of the LOD4 pass's
// triangles at street level. Their coarse levels take a fifth of the triangles: measured one
// part at a time on the default street, a fifth moved the image by under 0.01 dB but for the
// leaf's, 0.25 dB (docs/BENCHMARKS.md, "Coarser tree parts"). The leaf's took a third (0.06 dB)
// until trees showed their parts from every side; a fifth now costs 0.20 dB and the thesis
// street 5 % of its frame ("Trees from every side").
constexpr ShapeGenerator kGenerators[] = {
    {"bark", 16, bark, 0.2f},
    {"twig", 12, twig, 0.2f},
    {"leaf", 14, leaf, 0.2f},
    {"fruit", 12, fruit, 0.2f},
};

} // namespace

std::span<const ShapeGenerator> treeGenerators() {
    return kGenerators;
}

} // namespace hexlod::render
