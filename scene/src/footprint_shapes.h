// Footprint outlines shared by the demo footprints and the city's lots. Each lives in
// [0, w] x [0, d], counter-clockwise, with y = 0 on the street side.
#pragma once

#include <glm/glm.hpp>

#include <vector>

namespace hexlod::scene::detail {

using Polygon = std::vector<glm::dvec2>;

Polygon box(double w, double d);
Polygon lShape(double w, double d, double wing);
// Open towards the back of the lot, away from the street.
Polygon uShape(double w, double d, double wing);
// The stem faces the street, the bar fills the back of the lot.
Polygon tShape(double w, double d, double stem);

} // namespace hexlod::scene::detail
