// What a compiled grammar can produce at all: the rules reachable from its axiom and the
// terminal shapes those rules emit. A scene bakes impostors and loads meshes only for the
// shapes its grammars can emit (ARCHITECTURE.md §4, "Impostors"). The analysis is static and
// conservative: a Cond or Choose branch counts as reachable whatever its condition or
// probability.
#pragma once

#include "hexlod/grammar/compiled_grammar.h"

#include <vector>

namespace hexlod::grammar {

// reachable[r]: rule r is on some derivation path from the axiom.
std::vector<bool> reachableRules(const CompiledGrammar& grammar);

// emitted[s]: a reachable Shape rule emits shape s.
std::vector<bool> emittedShapes(const CompiledGrammar& grammar);

} // namespace hexlod::grammar
