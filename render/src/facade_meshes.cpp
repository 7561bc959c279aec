// Facade parts of the residential grammar (and the thesis example): the flat wall tile, sills
// and flower boxes, string-course ledges and cornices as extruded mouldings, fluted
// pilasters, balconies, awnings and entrance stairs. Mouldings are profiles in the (y, z)
// plane swept along x; the edge of a profile that lies on the wall is left open.
#include "shape_generators.h"

#include <algorithm>

namespace hexlod::render {
namespace {

// A moulding swept along the whole width, its end caps closed.
void moulding(MeshBuilder& b, const Profile& profile, uint32_t rgba) {
    b.sweep({.profile = profile.points,
             .pu = {0, 1, 0},
             .pv = {0, 0, 1},
             .axis = {1, 0, 0},
             .s0 = 0.0f,
             .s1 = b.W(),
             .openLast = true},
            rgba);
}

void wall(MeshBuilder& b, int) {
    b.quad({0, 0, 0}, {b.W(), 0, 0}, {b.W(), b.H(), 0}, {0, b.H(), 0}, {0, 0, 1}, palette::kPlaster);
}

// String course: a fillet, a cove, the vertical corona and an ovolo back to the wall.
void ledge(MeshBuilder& b, int detail) {
    const float H = b.H(), D = b.D();
    const int s = 1 + detail;
    Profile p;
    p.to(0, 0).to(0, 0.3f * D);
    p.arc({0, 0.75f * D}, {0.3f * H, 0.45f * D}, -90, 0, s);
    p.to(0.3f * H, D).to(0.75f * H, D);
    p.arc({0.75f * H, 0.7f * D}, {0.25f * H, 0.3f * D}, 90, 0, s);
    p.to(H, 0);
    moulding(b, p, palette::kLightStone);
}

// Crowning cornice: bed moulding, modillions under the corona, and a cyma on top.
void cornice(MeshBuilder& b, int detail) {
    const float W = b.W(), H = b.H(), D = b.D();
    Profile p;
    p.to(0, 0).to(0, 0.15f * D);
    p.arc({0, 0.4f * D}, {0.2f * H, 0.25f * D}, -90, 0, 3);
    p.to(0.2f * H, 0.45f * D).to(0.35f * H, 0.45f * D).to(0.35f * H, D).to(0.7f * H, D);
    p.arc({0.7f * H, 0.75f * D}, {0.3f * H, 0.25f * D}, 90, 0, 3);
    p.to(H, 0);
    moulding(b, p, palette::kLightStone);
    const int modillions = 6 + detail;
    const float half = 0.18f * W / float(modillions);
    for (int i = 0; i < modillions; ++i) {
        const float x = W * (float(i) + 0.5f) / float(modillions);
        b.box({x - half, 0.2f * H, 0.45f * D}, {x + half, 0.35f * H, 0.95f * D}, palette::kLightStone,
              kNegX | kPosX | kNegY | kPosZ);
    }
}

// Window sill: a drip groove under a rounded nose and a wash sloping back to the wall.
void windowSill(MeshBuilder& b, int detail) {
    const float H = b.H(), D = b.D();
    Profile p;
    p.to(0, 0)
        .to(0, 0.75f * D)
        .to(0.18f * H, 0.75f * D)
        .to(0.18f * H, 0.82f * D)
        .to(0, 0.82f * D)
        .to(0, 0.85f * D);
    p.arc({0.35f * H, 0.85f * D}, {0.35f * H, 0.15f * D}, 180, 0, 4 + detail);
    p.to(H, 0.1f * D).to(H, 0);
    moulding(b, p, palette::kLightStone);
}

void flowerBox(MeshBuilder& b, int detail) {
    const float W = b.W(), H = b.H(), D = b.D();
    b.box({0.03f * W, 0, 0.08f * D}, {0.97f * W, 0.55f * H, 0.95f * D}, palette::kTerracotta,
          kAllFaces & ~kPosY);
    b.quad({0.03f * W, 0.5f * H, 0.08f * D}, {0.97f * W, 0.5f * H, 0.08f * D},
           {0.97f * W, 0.5f * H, 0.95f * D}, {0.03f * W, 0.5f * H, 0.95f * D}, {0, 1, 0}, palette::kSoil);
    const int flowers = 4 + detail;
    for (int i = 0; i < flowers; ++i) {
        const float x =
            0.08f * W + 0.84f * W * (float(i) + 0.2f + 0.6f * detailJitter(i, 1)) / float(flowers);
        const float z = (0.3f + 0.4f * detailJitter(i, 2)) * D;
        const float rx = std::min(0.045f, 0.35f * W / float(flowers));
        b.sphere({x, 0.78f * H, z}, {rx, 0.2f * H, std::min(0.08f * D, rx)}, 4, 3,
                 i % 2 ? palette::kFlowerYellow : palette::kFlowerRed);
        b.twoSidedQuad({x - 2 * rx, 0.55f * H, z + 0.1f * D}, {x + 2 * rx, 0.55f * H, z + 0.1f * D},
                       {x + rx, 0.7f * H, z + 0.2f * D}, {x - rx, 0.7f * H, z + 0.2f * D}, {0, 0.3f, 1},
                       palette::kLeaf, palette::kLeafBack);
    }
}

// Pilaster: a fluted shaft on a moulded base under a capital and abacus.
void pillar(MeshBuilder& b, int detail) {
    const float W = b.W(), H = b.H(), D = b.D();
    b.box({0, 0, 0}, {W, 0.03f * H, D}, palette::kLightStone, kNoBack & ~kNegY);
    b.box({0.04f * W, 0.03f * H, 0}, {0.96f * W, 0.045f * H, 0.9f * D}, palette::kLightStone,
          kNoBack & ~kNegY);
    b.box({0.04f * W, 0.955f * H, 0}, {0.96f * W, 0.975f * H, 0.9f * D}, palette::kLightStone,
          kNoBack & ~kPosY);
    b.box({0, 0.975f * H, 0}, {W, H, D}, palette::kLightStone, kNoBack);
    const int flutes = 3 + detail;
    const float x0 = 0.1f * W, x1 = 0.9f * W, front = 0.75f * D;
    const float pitch = (x1 - x0) / float(flutes), flute = 0.7f * pitch;
    Profile p;
    p.to(x0, 0).to(x0, front);
    for (int f = 0; f < flutes; ++f) {
        const float xa = x0 + pitch * float(f) + 0.5f * (pitch - flute);
        p.to(xa, front);
        p.arc({xa + 0.5f * flute, front}, {0.5f * flute, 0.15f * D}, 180, 360, 3);
    }
    p.to(x1, front).to(x1, 0);
    b.sweep({.profile = p.points,
             .pu = {1, 0, 0},
             .pv = {0, 0, 1},
             .axis = {0, 1, 0},
             .s0 = 0.045f * H,
             .s1 = 0.955f * H,
             .caps = false,
             .openLast = true},
            palette::kLightStone);
}

// Balcony: a slab with a railing of top and bottom rails and balusters on three sides.
void balcony(MeshBuilder& b, int detail) {
    const float W = b.W(), H = b.H(), D = b.D();
    const float slab = 0.13f * H, rail = 0.025f * W, railDepth = 0.05f * D;
    b.box({0, 0, 0}, {W, slab, D}, palette::kLightStone, kNoBack);
    for (const auto& [y0, y1] : {std::pair{0.93f * H, H}, std::pair{slab, slab + 0.05f * H}}) {
        b.box({0, y0, D - railDepth}, {W, y1, D}, palette::kDarkMetal);
        b.box({0, y0, 0}, {rail, y1, D - railDepth}, palette::kDarkMetal, kNoBack);
        b.box({W - rail, y0, 0}, {W, y1, D - railDepth}, palette::kDarkMetal, kNoBack);
    }
    const int front = 8 + 2 * detail, side = 2 + detail / 2;
    const float r = 0.006f * W, y0 = slab + 0.05f * H, y1 = 0.93f * H;
    for (int i = 1; i <= front; ++i) {
        const float x = W * float(i) / float(front + 1);
        b.box({x - r, y0, D - 0.5f * railDepth - r}, {x + r, y1, D - 0.5f * railDepth + r},
              palette::kDarkMetal, kNegX | kPosX | kNegZ | kPosZ);
    }
    for (int i = 1; i <= side; ++i) {
        const float z = (D - railDepth) * float(i) / float(side + 1);
        for (const float x : {0.5f * rail, W - 0.5f * rail}) {
            b.box({x - r, y0, z - r}, {x + r, y1, z + r}, palette::kDarkMetal, kNegX | kPosX | kNegZ | kPosZ);
        }
    }
}

// Striped shop awning: canvas from the head box down and out, a scalloped valance, arms.
void awning(MeshBuilder& b, int detail) {
    const float W = b.W(), H = b.H(), D = b.D();
    b.box({0, 0.9f * H, 0}, {W, H, 0.08f * D}, palette::kDarkMetal, kNoBack);
    const int stripes = 4 + detail;
    const float top = 0.9f * H, front = 0.4f * H, hem = 0.12f * H, out = 0.97f * D;
    for (int i = 0; i < stripes; ++i) {
        const float xa = W * float(i) / float(stripes), xb = W * float(i + 1) / float(stripes);
        const uint32_t rgba = i % 2 ? palette::kFabricWhite : palette::kFabricRed;
        b.twoSidedQuad({xa, front, out}, {xb, front, out}, {xb, top, 0.08f * D}, {xa, top, 0.08f * D},
                       {0, 0.8f, 0.6f}, rgba, rgba);
        const glm::vec3 flap[5] = {{xa, front, out},
                                   {xa, hem + 0.1f * H, out},
                                   {0.5f * (xa + xb), hem, out},
                                   {xb, hem + 0.1f * H, out},
                                   {xb, front, out}};
        b.polygon(flap, {0, 0, 1}, rgba);
        b.polygon(flap, {0, 0, -1}, rgba);
    }
    const float radius = 0.012f;
    b.frustum({0, front, out - radius}, {W, front, out - radius}, radius, radius, 6, 1, palette::kDarkMetal,
              false, false);
    for (const float x : {0.05f * W, 0.95f * W}) {
        b.frustum({x, 0.1f * H, radius}, {x, front, out - 2.0f * radius}, radius, radius, 6, 1,
                  palette::kDarkMetal, false, false);
    }
}

// Entrance steps with nosings between two cheek walls; the top step meets the wall.
void stairs(MeshBuilder& b, int detail) {
    const float W = b.W(), H = b.H(), D = b.D();
    const int steps = 2 + detail;
    const float run = 0.94f * D / float(steps), cheek = 0.05f * W;
    for (int i = 0; i < steps; ++i) {
        const float top = H * float(steps - i) / float(steps), z0 = run * float(i), z1 = run * float(i + 1);
        b.box({cheek, 0, z0}, {W - cheek, top, z1}, palette::kStone, kNegX | kPosX | kPosY | kPosZ);
        b.box({cheek, top - 0.25f * H / float(steps), z1}, {W - cheek, top, z1 + 0.05f * D},
              palette::kLightStone, kAllFaces & ~kNegZ);
    }
    const glm::vec2 side[4] = {{0, 0}, {H, 0}, {H, run}, {0, 0.99f * D}};
    for (const float x0 : {0.0f, W - cheek}) {
        b.sweep({.profile = side,
                 .pu = {0, 1, 0},
                 .pv = {0, 0, 1},
                 .axis = {1, 0, 0},
                 .s0 = x0,
                 .s1 = x0 + cheek},
                palette::kStone);
    }
}

constexpr ShapeGenerator kGenerators[] = {
    {"wall", 0, wall},
    {"ledge", 8, ledge},
    {"cornice", 16, cornice},
    {"window_sill", 10, windowSill},
    {"flower_box", 10, flowerBox},
    {"pillar", 10, pillar},
    {"balcony", 12, balcony},
    {"awning", 12, awning},
    {"stairs", 6, stairs},
};

} // namespace

std::span<const ShapeGenerator> facadeGenerators() {
    return kGenerators;
}

} // namespace hexlod::render
