// Lowers one parsed rule to its CompiledRule, checking its arguments and successor arity.
// Internal to the grammar compiler.
#pragma once

#include "hexlod/grammar/ast.h"
#include "hexlod/grammar/compiled_grammar.h"

#include <unordered_map>

namespace hexlod::grammar {

using RuleIndexMap = std::unordered_map<std::string, uint32_t>;

// Returns false after reporting an error. Successor names are resolved through `rules`.
bool lowerRule(const RuleDecl& decl, const RuleIndexMap& rules, CompiledGrammar& grammar, CompiledRule& out,
               DiagnosticList& diagnostics);

} // namespace hexlod::grammar
