// Bounds of a terminal set's arena pages, for culling a page of HEXLOD_ARENA_PAGE terminals
// whole before the per-terminal pass (cluster culling, as meshlet renderers cull clusters
// before their triangles, by their bounds and their normal cone). Records are sorted by shape,
// then building, so a page is one or a few buildings' windows on one or two walls, or one
// tree's leaves: a tight sphere, few normals, few building ids.
#pragma once

#include "hexlod/grammar/terminal_set.h"
#include "hexlod/lod/cull_shared.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <vector>

namespace hexlod::lod {

// What the cull knows of a page (records [64 p, 64 p + 64)) before it reads one terminal.
struct PageBounds {
    // A sphere in the set's cell-local coordinates (xyz, radius) that holds the sphere
    // classifyTerminal tests for each of the page's terminals, padded so that float rounding in
    // either test cannot make the page test the stricter one. A page with a non-finite size or
    // position gets an infinite radius: it is never culled whole.
    glm::vec4 sphere{0.0f};
    // The box around those spheres, padded likewise: a page of one wall is a thin slab, which
    // its sphere bounds loosely.
    glm::vec3 boxMin{0.0f}, boxMax{0.0f};
    // The page's wall planes, for backface culling it whole: each terminal's axisZ (the normal
    // its wall faces) is one of the first `faceCount` faces' xyz, and each face's w is the
    // least, over its terminals, of dot(normal, corner) - depth, cell-local. 0 faces: the page
    // holds more normals than this (a tree's leaves) or a non-finite record, and is never
    // culled whole for facing away.
    glm::vec4 faces[2]{};
    uint32_t faceCount = 0;
    // The least and greatest building id of its records (tree ids for tree parts).
    uint32_t firstBuilding = 0, lastBuilding = 0;
};

std::vector<PageBounds> pageBounds(const grammar::TerminalSet& set);

// False only when `sphere`, in a batch whose cell origin minus the camera is `origin`, lies
// wholly outside a frustum plane of `frame`, so that classifyTerminal would cull each of the
// page's terminals.
bool pageMayBeVisible(const glm::vec4& sphere, const glm::vec3& origin, const shared::CullFrame& frame);
// The same for a page, by its sphere and then its box.
bool pageMayBeVisible(const PageBounds& page, const glm::vec3& origin, const shared::CullFrame& frame);

// True only when the camera lies behind every face of the page (PageBounds::faces) by more than
// the terminals' depth, so that classifyTerminal's backface test culls each of its terminals.
bool pageFacesAway(const PageBounds& page, const glm::vec3& origin);

// False only when every point of `sphere` lies at or beyond LOD3's distance from the camera, so
// that classifyTerminal gives none of the page's terminals of a shape with an impostor LOD4.
bool pageMayHoldLod4(const glm::vec4& sphere, const glm::vec3& origin, const shared::CullFrame& frame);

// False only when classifyTerminal gives none of the page's terminals LOD3: every point of
// `sphere` lies at or beyond LOD2's distance, or the frame has no LOD distances.
bool pageMayHoldLod3(const glm::vec4& sphere, const glm::vec3& origin, const shared::CullFrame& frame);

} // namespace hexlod::lod
