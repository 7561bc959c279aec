// Bounds of a terminal set's arena pages, for culling a page of HEXLOD_ARENA_PAGE terminals
// whole before the per-terminal pass (cluster culling, as meshlet renderers cull clusters
// before their triangles). Records are sorted by shape, then building, so a page is one or a
// few buildings' windows, or one tree's leaves: a tight sphere.
#pragma once

#include "hexlod/grammar/terminal_set.h"
#include "hexlod/lod/cull_shared.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <vector>

namespace hexlod::lod {

// Per page (records [64 p, 64 p + 64)): a sphere in the set's cell-local coordinates (xyz,
// radius) that holds the sphere classifyTerminal tests for each of its terminals, padded so
// that float rounding in either test cannot make the page test the stricter one. A page with
// a non-finite size or position gets an infinite radius: it is never culled whole.
std::vector<glm::vec4> pageSpheres(const grammar::TerminalSet& set);

// False only when `sphere`, in a batch whose cell origin minus the camera is `origin`, lies
// wholly outside a frustum plane of `frame`, so that classifyTerminal would cull each of the
// page's terminals.
bool pageMayBeVisible(const glm::vec4& sphere, const glm::vec3& origin, const shared::CullFrame& frame);

// False only when every point of `sphere` lies at or beyond LOD3's distance from the camera, so
// that classifyTerminal gives none of the page's terminals of a shape with an impostor LOD4.
bool pageMayHoldLod4(const glm::vec4& sphere, const glm::vec3& origin, const shared::CullFrame& frame);

// False only when classifyTerminal gives none of the page's terminals LOD3: every point of
// `sphere` lies at or beyond LOD2's distance, or the frame has no LOD distances.
bool pageMayHoldLod3(const glm::vec4& sphere, const glm::vec3& origin, const shared::CullFrame& frame);

} // namespace hexlod::lod
