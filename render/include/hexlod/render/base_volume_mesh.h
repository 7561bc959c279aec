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

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace hexlod::render {

// One building's part of a base volume mesh: its run of indices (a building's triangles are
// contiguous) and the cell-local bounds of its vertices, so that a renderer can leave out the
// buildings that nearer geometry hides instead of the whole batch or nothing. A building a
// few pixels across may be drawn as one point (lod/building_points.h), whose area and colour
// come from its lowest band's footprint and its walls' colour.
struct VolumeBuilding {
    uint32_t firstIndex = 0, indexCount = 0;
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};
    float footprintArea = 0.0f, footprintPerimeter = 0.0f; // square metres, metres
    uint32_t wallColour = 0;                               // rgba8, as the mesh's walls
};

// The colour of base volume roofs (rgba8).
uint32_t roofColour();

// Wall colour of a wall material index (the grammars' `wall_material`, 0..7; others wrap).
uint32_t wallMaterialColour(uint16_t material);

// Every building of `set` in one mesh. Positions are cell-local metres (the set's frame, not
// unit scope space) and normals are unit world normals. `inset` moves the walls and caps that
// far inwards (0 for LOD0; about half a metre under terminals, so that recessed glass stays in
// front of the shell instead of z-fighting with it); a band too small to inset keeps its outline.
// A wall's uv is (index of its element in set.elements, 1), every other vertex's (-1, 0): LOD1
// resumes that element's grammar per pixel. With `buildings`, also each building's part, in
// index order (buildings without a closed band have none).
TerminalMesh buildBaseVolumes(const grammar::ExtrudedSet& set, float inset,
                              std::vector<VolumeBuilding>* buildings = nullptr);

} // namespace hexlod::render
