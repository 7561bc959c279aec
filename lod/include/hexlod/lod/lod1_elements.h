// An extruded set's elements as LOD1 reads them on the GPU: per element its frame, size and
// the derivation state the grammar resumes from (lod1.frag's Lod1Element, std430).
#pragma once

#include "hexlod/grammar/extruded_set.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace hexlod::lod {

struct GpuLod1Element {
    glm::vec4 origin;  // xyz: cell-local; w: the building's base elevation
    glm::vec4 axisX;   // xyz; w: size along x
    glm::vec4 axisY;   // xyz; w: size along y
    glm::uvec4 rule;   // x: stop rule; y: first parameter; z, w: the building key (lo, hi)
    glm::ivec4 state;  // floor, floors, index, count
    glm::uvec4 state2; // level, depth, atom, atoms
    glm::uvec4 state3; // x: building id; y, z: scope key (lo, hi); w: 0
};
static_assert(sizeof(GpuLod1Element) == 112);

// One entry per element of `set`, in its order (the index walls carry in their uv).
std::vector<GpuLod1Element> packLod1Elements(const grammar::ExtrudedSet& set, uint64_t seed);

} // namespace hexlod::lod
