// How far apart two meshes of one terminal shape lie: what drawing one in place of the other
// can move a point of the surface, per unit-scope axis, so that a terminal's own scope turns it
// into metres (a terminal stretches the unit mesh by its width, height and depth).
#pragma once

#include "hexlod/render/terminal_mesh.h"

#include <glm/vec3.hpp>

namespace hexlod::render {

// A symmetric, sampled Hausdorff distance. The samples are every vertex, edge midpoint and
// triangle centroid of each mesh; each is matched with its closest point on the other mesh's
// triangles at `a`'s nominal size, and the result is the largest |difference| along u, v and t
// over all matches, in unit scope space. It bounds how far a terminal of scope (w, h, d) moves
// a sample: |(u·w, v·h, t·d)| of the result. A mesh without triangles is infinitely far from one with
// triangles, and zero from another without.
glm::vec3 meshDeviation(const TerminalMesh& a, const TerminalMesh& b);

} // namespace hexlod::render
