// The GLSL half of LOD1 (Marvie et al. 2011): from a compiled grammar, the tables of its flat
// rule map and one GLSL expression per rule argument, translated from the bytecode, for the
// interpreter in lod1.glsl. One program per grammar: a scene compiles as many LOD1 shaders as
// it has building grammars with buildings.
#pragma once

#include "hexlod/grammar/compiled_grammar.h"

#include <string>

namespace hexlod::lod {

// GLSL defining lod1Rule* tables, lod1Successors, lod1ArgumentRelative,
// `void lod1LoadParameters(uint first)` (the building's parameters the expressions read, from
// the parameter buffer into lod1Parameter[], once per pixel) and
// `float lod1Argument(uint argument, Lod1Scope s, Lod1Context c, uint64_t randomKey)`.
std::string generateLod1Grammar(const grammar::CompiledGrammar& grammar);

// The bytecode of one expression as a GLSL expression over `s`, `c` and `randomKey`
// (exposed for tests: the translation is checked against grammar::evaluate).
std::string expressionToGlsl(const grammar::CompiledGrammar& grammar, const grammar::Expression& expression);

} // namespace hexlod::lod
