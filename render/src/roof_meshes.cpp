// Roof parts of the residential grammar: the tiled slope, chimney stacks and the parapet of
// flat roofs. A roof tile's scope lies on the slope: x along the eaves, y up the slope, z the
// slope's normal.
#include "shape_generators.h"

#include <cmath>

namespace hexlod::render {
namespace {

// The residential grammar's default roof pitch: chimneys are built to stand plumb at it.
constexpr float kDefaultPitchDegrees = 38.0f;

// Barrel tiles in overlapping courses, as a height field: a half-wave across each barrel and a
// ridge at each course line.
void roofTile(MeshBuilder& b, int detail) {
    const float W = b.W(), H = b.H(), D = b.D();
    const int barrels = 3, courses = 5 + detail;
    const float course = H / float(courses);
    // Two grid rows per course: its proud lower edge and its lap under the next course.
    b.heightField(
        0, W, 0, H, 2 * barrels, 2 * courses,
        [&](float x, float y) {
            const float wave = std::abs(std::sin(3.14159265f * float(barrels) * x / W));
            const float lap = 0.5f + 0.5f * std::cos(2.0f * 3.14159265f * y / course);
            return D * (0.15f + 0.45f * wave + 0.35f * lap);
        },
        palette::kTerracotta);
}

// A brick stack leaning up the slope so that it stands plumb at the default pitch, with a
// plinth, a cap and two pots.
void chimney(MeshBuilder& b, int detail) {
    const float W = b.W(), H = b.H(), D = b.D();
    const float lean = std::tan(glm::radians(kDefaultPitchDegrees)); // y per unit of z
    const float x0 = 0.35f * W, x1 = 0.65f * W, y0 = 0.02f * H, y1 = 0.25f * H, top = 0.6f * D;
    const glm::vec3 axis(0, lean, 1);
    const auto stack = [&](float grow, float from, float to, uint32_t rgba) {
        const glm::vec2 outline[4] = {
            {x0 - grow, y0 - grow}, {x1 + grow, y0 - grow}, {x1 + grow, y1 + grow}, {x0 - grow, y1 + grow}};
        b.sweep({.profile = outline, .axis = axis, .s0 = from, .s1 = to}, rgba);
    };
    stack(0.02f, 0.0f, 0.08f * D, palette::kDarkMetal); // lead flashing
    stack(0.0f, 0.08f * D, top, palette::kBrick);
    stack(0.03f, top, top + 0.06f * D, palette::kLightStone);
    const int segments = 6 + detail;
    for (const float x : {0.43f * W, 0.57f * W}) {
        const float z0 = top + 0.06f * D, z1 = top + 0.18f * D;
        const glm::vec3 base(x, 0.5f * (y0 + y1) + lean * z0, z0), tip(x, 0.5f * (y0 + y1) + lean * z1, z1);
        b.frustum(base, tip, 0.05f, 0.04f, segments, 1, palette::kTerracotta, false, true);
    }
}

// The parapet of a flat roof: a wall behind the facade plane (t in [-1, 0]) with piers on its
// outer face and a coping with drips on both sides.
void parapet(MeshBuilder& b, int detail) {
    const float W = b.W(), H = b.H(), D = b.D(), coping = 0.85f * H;
    b.box({0, 0, -D * 0.9f}, {W, coping, 0}, palette::kPlaster, kAllFaces & ~kNegY);
    Profile p;
    p.to(coping, -D).to(coping, 0.25f * D).to(coping + 0.05f * H, 0.25f * D).to(coping + 0.05f * H, 0.2f * D);
    p.to(H, 0.1f * D).to(H, -0.85f * D).to(coping + 0.05f * H, -0.95f * D).to(coping + 0.05f * H, -D);
    b.sweep({.profile = p.points, .pu = {0, 1, 0}, .pv = {0, 0, 1}, .axis = {1, 0, 0}, .s0 = 0.0f, .s1 = W},
            palette::kLightStone);
    const int piers = 2 + detail;
    for (int i = 0; i < piers; ++i) {
        const float x = W * (float(i) + 0.5f) / float(piers), half = 0.15f;
        b.box({x - half, 0, 0}, {x + half, coping, 0.15f * D}, palette::kPlaster,
              kNegX | kPosX | kPosZ | kPosY);
    }
}

constexpr ShapeGenerator kGenerators[] = {
    {"roof_tile", 20, roofTile},
    {"chimney", 8, chimney},
    {"parapet", 8, parapet},
};

} // namespace

std::span<const ShapeGenerator> roofGenerators() {
    return kGenerators;
}

} // namespace hexlod::render
