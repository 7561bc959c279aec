// LOD1's per-pixel grammar (Marvie et al. 2011, algorithm 1) on the CPU: from a point on an
// extruded-set element (a facade face), resume the grammar at the element's stop rule and
// descend only into the successor that contains the point, through Split, Repeat, Cond and
// Choose, until a Shape names the terminal there. The GLSL interpreter (lod1.glsl with the
// tables lod1_codegen generates) takes the same steps; this is its reference, and the tests'
// link between the terminal set and what LOD1 draws.
#pragma once

#include "hexlod/grammar/compiled_grammar.h"
#include "hexlod/grammar/extruded_set.h"

#include <glm/vec2.hpp>

#include <cstdint>

namespace hexlod::lod {

enum class Lod1Outcome : uint8_t {
    Terminal, // a Shape rule: `shape`, `scopeOrigin`, `scopeSize` say which terminal and where
    Empty,    // NULL, a part of size 0, or outside every part: nothing but the wall
    Stopped,  // a rule outside the face-planar subset (Extrude, Rotate, Branch, ...), or the
              // step cap: LOD1 shows the wall there
};

struct Lod1Hit {
    Lod1Outcome outcome = Lod1Outcome::Empty;
    uint32_t rule = 0; // the last rule applied
    uint16_t shape = 0;
    glm::vec2 scopeOrigin{0.0f}, scopeSize{0.0f}; // the terminal's scope in the element's face coordinates
    uint32_t steps = 0;
};

inline constexpr uint32_t kLod1MaxSteps = 64;

// `point` is in the element's face coordinates: metres along its x and y axes from its origin.
// `building` is the element's building in `set`; `seed` the scene seed.
Lod1Hit lod1Query(const grammar::CompiledGrammar& grammar, const grammar::ExtrudedSet& set, uint32_t building,
                  uint32_t element, glm::vec2 point, uint64_t seed);

} // namespace hexlod::lod
