// Static check that every rule can end: recursion must pass through a Cond or a Choose
// with an alternative that terminates. Internal to the grammar compiler.
#pragma once

#include "hexlod/grammar/compiled_grammar.h"

namespace hexlod::grammar {

// Reports one "unbounded recursion" error per rule cycle that can never terminate.
void checkTermination(const CompiledGrammar& grammar, DiagnosticList& diagnostics);

} // namespace hexlod::grammar
