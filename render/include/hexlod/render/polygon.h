// Simple-polygon helpers shared by the mesh generators (profile caps) and the base volumes of
// the extruded set (roof caps of L, U and T footprints): ear-clipping triangulation (Meisters
// 1975, "Polygons have ears") and an inward mitred offset.
#pragma once

#include <glm/vec2.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace hexlod::render {

// Twice the signed area: positive for counter-clockwise.
double signedArea2(std::span<const glm::vec2> polygon);

// Triangles (indices into `polygon`, counter-clockwise whatever the input winding) of a
// simple polygon without repeated closing point. A polygon that is not simple still yields
// triangles covering it as well as ear clipping can; never loops forever. Fewer than 3
// points give none.
std::vector<uint32_t> triangulatePolygon(std::span<const glm::vec2> polygon);

// The counter-clockwise polygon moved inwards by `distance` along each edge's normal, with
// mitred corners. Returns the input unchanged when the offset would turn an edge around,
// spike a corner further than 4 × distance or flip the polygon (edges shorter than the inset).
std::vector<glm::vec2> insetPolygon(std::span<const glm::vec2> polygon, float distance);

} // namespace hexlod::render
