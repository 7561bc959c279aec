// Openings: windows (casement, sash, arched), French and shop windows, lobby glazing, doors
// and shutters. A window fills its scope, which is the hole in the wall: a moulded surround
// stands out of the wall plane, the reveal runs back to the frame, and the glass lies behind
// the wall plane (t < 0), as in a real facade.
#include "hexlod/render/polygon.h"
#include "shape_generators.h"

#include <algorithm>

namespace hexlod::render {
namespace {

struct Opening {
    float surround = 0.07f;       // architrave width, share of min(W, H); 0 for none
    float surroundDepth = 0.45f;  // its protrusion, share of D
    float reveal = 0.7f;          // depth of the frame behind the wall plane, share of D
    float frame = 0.045f;         // frame width, share of min(W, H)
    int leavesX = 2, leavesY = 1; // opening sashes or fixed lights
    int barsX = 0, barsY = 0;     // glazing bars per leaf
    float transom = 0.0f;         // share of the glazed height given to a fixed top light
    float panel = 0.0f;           // share of each leaf that is a solid bottom panel
    float archRise = 0.0f;        // arched head, share of W; 0 for a flat head
    int arcSegments = 8;
    bool handles = true;
    uint32_t frameRgba = palette::kWhiteFrame;
    uint32_t surroundRgba = palette::kLightStone;
};

std::vector<glm::vec2> outlineOf(const Opening& o, float x0, float y0, float x1, float y1) {
    if (o.archRise <= 0.0f) return rectangleOutline(x0, y0, x1, y1);
    const float rise = std::min(o.archRise * (x1 - x0), 0.5f * (x1 - x0));
    return archOutline(x0, y0, x1, y1, std::min(rise, 0.9f * (y1 - y0)), o.arcSegments);
}

// A sash or fixed light: frame bars around glass, glazing bars, an optional solid panel.
void leaf(MeshBuilder& b, const Opening& o, glm::vec2 lo, glm::vec2 hi, float z, float bar, int column) {
    const float depth = 0.12f * b.D();
    const std::vector<glm::vec2> outer = rectangleOutline(lo.x, lo.y, hi.x, hi.y);
    const std::vector<glm::vec2> inner = insetPolygon(outer, bar);
    b.ring(outer, inner, z - depth, z + depth, o.frameRgba);
    const glm::vec2 glassLo = inner[0], glassHi = inner[2];
    float glassBottom = glassLo.y;
    if (o.panel > 0.0f) {
        glassBottom = glassLo.y + o.panel * (glassHi.y - glassLo.y);
        b.box({glassLo.x, glassLo.y, z - depth}, {glassHi.x, glassBottom, z + 0.5f * depth}, o.frameRgba,
              kNoBack);
    }
    b.quad({glassLo.x, glassBottom, z}, {glassHi.x, glassBottom, z}, {glassHi.x, glassHi.y, z},
           {glassLo.x, glassHi.y, z}, {0, 0, 1}, palette::kGlass);
    const float thin = 0.35f * bar;
    for (int i = 1; i <= o.barsX; ++i) {
        const float x = glassLo.x + (glassHi.x - glassLo.x) * float(i) / float(o.barsX + 1);
        b.box({x - 0.5f * thin, glassBottom, z}, {x + 0.5f * thin, glassHi.y, z + 0.7f * depth}, o.frameRgba,
              kNoBack);
    }
    for (int i = 1; i <= o.barsY; ++i) {
        const float y = glassBottom + (glassHi.y - glassBottom) * float(i) / float(o.barsY + 1);
        b.box({glassLo.x, y - 0.5f * thin, z}, {glassHi.x, y + 0.5f * thin, z + 0.7f * depth}, o.frameRgba,
              kNoBack);
    }
    if (o.handles) {
        const float x = column % 2 == 0 ? hi.x - 0.5f * bar : lo.x + 0.5f * bar;
        const float y = 0.5f * (lo.y + hi.y);
        b.box({x - 0.25f * bar, y - 1.5f * bar, z + depth},
              {x + 0.25f * bar, y + 1.5f * bar, z + 1.8f * depth}, palette::kSteel, kNoBack);
    }
}

void opening(MeshBuilder& b, const Opening& o) {
    const float W = b.W(), H = b.H(), D = b.D(), unit = std::min(W, H);
    std::vector<glm::vec2> hole = outlineOf(o, 0, 0, W, H);
    if (o.surround > 0.0f) {
        const std::vector<glm::vec2> inner = insetPolygon(hole, o.surround * unit);
        b.ring(hole, inner, 0.0f, o.surroundDepth * D, o.surroundRgba);
        hole = inner;
    }
    const float back = -o.reveal * D;
    b.sweep({.profile = hole, .axis = {0, 0, 1}, .s0 = back, .s1 = 0.0f, .caps = false, .inward = true},
            palette::kPlaster);
    const float bar = o.frame * unit;
    const std::vector<glm::vec2> light = insetPolygon(hole, bar);
    b.ring(hole, light, back, back + 0.25f * D, o.frameRgba);
    const float glassZ = back + 0.12f * D;
    // The sashes fill the rectangle under the spring line (arched) or the transom.
    const glm::vec2 lo = light[0], hi = light[2];
    float top = hi.y;
    if (o.transom > 0.0f || o.archRise > 0.0f) {
        top = o.archRise > 0.0f ? hi.y - bar : hi.y - o.transom * (hi.y - lo.y);
        b.box({lo.x, top, back}, {hi.x, top + bar, back + 0.25f * D}, o.frameRgba, kNoBack);
        std::vector<glm::vec3> fixedLight;
        for (const glm::vec2& p : light) {
            if (p.y > top + bar) fixedLight.push_back({p, glassZ});
        }
        fixedLight.insert(fixedLight.begin(), {{lo.x, top + bar, glassZ}, {hi.x, top + bar, glassZ}});
        if (o.archRise <= 0.0f)
            fixedLight = {{lo.x, top + bar, glassZ},
                          {hi.x, top + bar, glassZ},
                          {hi.x, hi.y, glassZ},
                          {lo.x, hi.y, glassZ}};
        b.polygon(fixedLight, {0, 0, 1}, palette::kGlass);
    }
    for (int j = 0; j < o.leavesY; ++j) {
        for (int i = 0; i < o.leavesX; ++i) {
            const glm::vec2 leafLo(lo.x + (hi.x - lo.x) * float(i) / float(o.leavesX),
                                   lo.y + (top - lo.y) * float(j) / float(o.leavesY));
            const glm::vec2 leafHi(lo.x + (hi.x - lo.x) * float(i + 1) / float(o.leavesX),
                                   lo.y + (top - lo.y) * float(j + 1) / float(o.leavesY));
            // Sliding sashes sit one behind the other.
            leaf(b, o, leafLo, leafHi, glassZ - 0.1f * D * float(j % 2), bar, i);
        }
    }
}

void casementWindow(MeshBuilder& b, int detail) {
    opening(b, {.barsX = detail / 2, .barsY = (detail + 1) / 2, .transom = 0.28f});
}

void sashWindow(MeshBuilder& b, int detail) {
    opening(b, {.surround = 0.09f,
                .leavesX = 1,
                .leavesY = 2,
                .barsX = 1 + detail / 2,
                .barsY = (detail + 1) / 2,
                .handles = false});
}

void archedWindow(MeshBuilder& b, int detail) {
    opening(b, {.barsY = 1 + detail / 2, .archRise = 0.5f, .arcSegments = 6 + 2 * ((detail + 1) / 2)});
}

// The thesis example's window (thesis §4.6.1): a plain two-light casement.
void thesisWindow(MeshBuilder& b, int detail) {
    opening(b, {.surround = 0.05f,
                .barsX = detail / 2,
                .barsY = (detail + 1) / 2,
                .transom = 0.25f,
                .frameRgba = palette::kBrownWood});
}

void balconyDoor(MeshBuilder& b, int detail) {
    opening(b, {.surround = 0.05f,
                .reveal = 0.6f,
                .barsY = 1 + detail,
                .panel = 0.3f,
                .frameRgba = palette::kBrownWood});
}

void shopWindow(MeshBuilder& b, int detail) {
    opening(b, {.surround = 0.06f,
                .surroundDepth = 0.8f,
                .reveal = 0.5f,
                .frame = 0.035f,
                .leavesX = 3,
                .barsY = detail,
                .transom = 0.2f,
                .panel = 0.22f,
                .handles = false,
                .frameRgba = palette::kGreenWood,
                .surroundRgba = palette::kGreenWood});
}

void lobbyGlass(MeshBuilder& b, int detail) {
    opening(b, {.surround = 0.0f,
                .reveal = 0.8f,
                .frame = 0.02f,
                .leavesX = 1,
                .barsX = 1 + detail,
                .barsY = 1,
                .handles = false,
                .frameRgba = palette::kAluminium});
}

// A panelled door set back in its reveal, with a fanlight.
void door(MeshBuilder& b, int detail) {
    const float W = b.W(), H = b.H(), D = b.D(), unit = std::min(W, H);
    const std::vector<glm::vec2> hole = rectangleOutline(0, 0, W, H);
    const std::vector<glm::vec2> opening = insetPolygon(hole, 0.06f * unit);
    b.ring(hole, opening, 0.0f, 0.6f * D, palette::kLightStone);
    const float back = -0.7f * D;
    b.sweep({.profile = opening, .axis = {0, 0, 1}, .s0 = back, .s1 = 0.0f, .caps = false, .inward = true},
            palette::kPlaster);
    const glm::vec2 lo = opening[0], hi = opening[2];
    const float fanlight = hi.y - 0.14f * (hi.y - lo.y), bar = 0.04f * unit;
    b.box({lo.x, fanlight, back}, {hi.x, fanlight + bar, back + 0.3f * D}, palette::kBrownWood, kNoBack);
    b.quad({lo.x, fanlight + bar, back}, {hi.x, fanlight + bar, back}, {hi.x, hi.y, back}, {lo.x, hi.y, back},
           {0, 0, 1}, palette::kGlass);
    b.quad({lo.x, lo.y, back}, {hi.x, lo.y, back}, {hi.x, fanlight, back}, {lo.x, fanlight, back}, {0, 0, 1},
           palette::kBrownWood);
    // Raised panels, two columns.
    const int rows = 1 + detail / 2;
    const float margin = 0.1f * (hi.x - lo.x), gap = 0.06f * (hi.x - lo.x);
    const float panelW = 0.5f * (hi.x - lo.x - 2.0f * margin - gap);
    const float panelH = (fanlight - lo.y - 2.0f * margin - gap * float(rows - 1)) / float(rows);
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < 2; ++c) {
            const float x0 = lo.x + margin + float(c) * (panelW + gap),
                        y0 = lo.y + margin + float(r) * (panelH + gap);
            const std::vector<glm::vec2> panel = rectangleOutline(x0, y0, x0 + panelW, y0 + panelH);
            const std::vector<glm::vec2> field = insetPolygon(panel, 0.2f * std::min(panelW, panelH));
            b.ring(panel, field, back, back + 0.15f * D, palette::kBrownWood);
            b.quad({field[0], back + 0.15f * D}, {field[1], back + 0.15f * D}, {field[2], back + 0.15f * D},
                   {field[3], back + 0.15f * D}, {0, 0, 1}, palette::kBrownWood);
        }
    }
    const float knobY = lo.y + 0.45f * (fanlight - lo.y);
    b.box({hi.x - 2.5f * bar, knobY - bar, back}, {hi.x - 1.5f * bar, knobY + bar, back + 0.45f * D},
          palette::kSteel, kNoBack);
    if (detail % 2) { // a letter plate
        const float cx = 0.5f * (lo.x + hi.x), y = lo.y + 0.5f * (fanlight - lo.y);
        b.box({cx - 3.0f * bar, y - 0.6f * bar, back}, {cx + 3.0f * bar, y + 0.6f * bar, back + 0.3f * D},
              palette::kSteel, kNoBack);
    }
}

// A louvred shutter standing on the wall beside a window.
void shutter(MeshBuilder& b, int detail) {
    const float W = b.W(), H = b.H(), D = b.D();
    const std::vector<glm::vec2> outer = rectangleOutline(0, 0, W, H);
    const float stile = 0.16f * W;
    const std::vector<glm::vec2> inner = insetPolygon(outer, stile);
    b.ring(outer, inner, 0.0f, D, palette::kGreenWood);
    const glm::vec2 lo = inner[0], hi = inner[2];
    const float middle = 0.5f * (lo.y + hi.y);
    b.box({lo.x, middle - 0.5f * stile, 0.1f * D}, {hi.x, middle + 0.5f * stile, 0.9f * D},
          palette::kGreenWood, kNoBack);
    const int slats = 6 + 2 * detail;
    for (int half = 0; half < 2; ++half) {
        const float y0 = half ? middle + 0.5f * stile : lo.y, y1 = half ? hi.y : middle - 0.5f * stile;
        const float pitch = (y1 - y0) / float(slats / 2);
        for (int s = 0; s < slats / 2; ++s) {
            const float y = y0 + pitch * (float(s) + 0.5f);
            // A slat tilted about 45 degrees, its outer edge lower so rain runs off.
            const glm::vec2 slat[4] = {{y - 0.5f * pitch, 0.85f * D},
                                       {y - 0.3f * pitch, 0.85f * D},
                                       {y + 0.5f * pitch, 0.15f * D},
                                       {y + 0.3f * pitch, 0.15f * D}};
            b.sweep({.profile = slat,
                     .pu = {0, 1, 0},
                     .pv = {0, 0, 1},
                     .axis = {1, 0, 0},
                     .s0 = lo.x,
                     .s1 = hi.x,
                     .caps = false},
                    palette::kGreenWood);
        }
    }
}

constexpr ShapeGenerator kGenerators[] = {
    {"window_casement", 8, casementWindow},
    {"window_sash", 8, sashWindow},
    {"window_arched", 8, archedWindow},
    {"window", 8, thesisWindow},
    {"balcony_door", 6, balconyDoor},
    {"shop_window", 6, shopWindow},
    {"lobby_glass", 8, lobbyGlass},
    {"door", 7, door},
    {"shutter", 12, shutter},
};

} // namespace

std::span<const ShapeGenerator> windowGenerators() {
    return kGenerators;
}

} // namespace hexlod::render
