// How a building's storey count reaches its grammar: one rule shared by the scene builder
// and `hexlod expand --footprints`.
#pragma once

#include "hexlod/grammar/compiled_grammar.h"

#include <vector>

namespace hexlod::scene {

// Storeys of an imported building: `building:levels` if known, else height / the grammar's
// `floor_h` default; NaN when neither is known (the building keeps the scene's default).
double floorsFromImport(const grammar::CompiledGrammar& g, double height, double levels);

// Appends `floors` (rounded, clamped into the declared range) when the grammar declares a
// `floors` parameter and `floors` is finite. Generated and imported storey counts are
// suggestions, not user input, so they are fitted to the grammar rather than rejected.
void appendFloors(const grammar::CompiledGrammar& g, double floors,
                  std::vector<grammar::ParameterOverride>& list);

} // namespace hexlod::scene
