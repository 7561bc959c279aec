// How far apart two meshes of one terminal shape lie: what drawing one in place of the other
// can move a point of the surface, per unit-scope axis, so that a terminal's own scope turns it
// into metres (a terminal stretches the unit mesh by its width, height and depth).
#pragma once

#include "hexlod/render/terminal_mesh.h"

#include <glm/vec3.hpp>

namespace hexlod::render {

// A symmetric, sampled Hausdorff distance that sees appearance as well as shape. The samples
// are every vertex, edge midpoint and triangle centroid of each mesh; each is matched with its
// closest point on those triangles of the other mesh that look like its own (the same colour
// within about 5 levels of 255 per linear channel, a shading normal within about 37 degrees),
// at `a`'s nominal size. The result is the largest |difference| along u, v and t over all
// matches, in unit scope space: a dropped mullion counts as far as the nearest frame of its
// colour, not as the glass behind it. It bounds how far a terminal of scope (w, h, d) moves a
// sample: |(u·w, v·h, t·d)| of the result. A sample with no look-alike triangle makes it
// infinite; so does a mesh without triangles against one with, and two without are zero apart.
glm::vec3 meshDeviation(const TerminalMesh& a, const TerminalMesh& b);

} // namespace hexlod::render
