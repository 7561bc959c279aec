// What a tree species looks like from each of its impostor's views, reduced to one texel: the
// covered texels' mean albedo, the share of the view they cover, and their mean normal. A
// tree a pixel or two across shows no more than that (the point form, tree_point.vert).
#pragma once

#include "hexlod/impostor/impostor_atlas.h"

#include <glm/vec4.hpp>

#include <vector>

namespace hexlod::lod {

// Two vec4 per view, in view order: (mean albedo, coverage in [0, 1]) and (mean shape-space
// normal, unnormalised; 0). An empty view gives zeros.
std::vector<glm::vec4> treeViewAverages(const impostor::ImpostorAtlas& atlas);

} // namespace hexlod::lod
