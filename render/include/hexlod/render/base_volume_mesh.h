// Base volumes of an extruded set as triangles: the closed shell of each building that LOD0
// draws, and that a full-detail export puts under the terminals so that roofs are closed.
//
// The shell is rebuilt from the extruded set's elements rather than from the footprint alone,
// so setback towers keep their steps: elements that entered the same stop rule at the same
// elevation (one per footprint edge) form one storey band, lofted from the ring of their bottom
// edges to the ring of their top edges (a leaning crown leans), and capped at its top. Bands
// with fewer than three faces (roof edges, tree trunks) add nothing.
#pragma once

#include "hexlod/grammar/extruded_set.h"
#include "hexlod/render/terminal_mesh.h"

namespace hexlod::render {

// Wall colour of a wall material index (the grammars' `wall_material`, 0..7; others wrap).
uint32_t wallMaterialColour(uint16_t material);

// Every building of `set` in one mesh. Positions are cell-local metres (the set's frame, not
// unit scope space) and normals are unit world normals. `inset` moves the walls and caps that
// far inwards (0 for LOD0; about half a metre under terminals, so that recessed glass stays in
// front of the shell instead of z-fighting with it); a band too small to inset keeps its outline.
// A wall's uv is (index of its element in set.elements, 1), every other vertex's (-1, 0): LOD1
// resumes that element's grammar per pixel.
TerminalMesh buildBaseVolumes(const grammar::ExtrudedSet& set, float inset);

} // namespace hexlod::render
