// Lowers expression trees to bytecode with type checking (number vs boolean) and
// constant folding. Internal to the grammar compiler.
#pragma once

#include "hexlod/grammar/ast.h"
#include "hexlod/grammar/compiled_grammar.h"

#include <optional>

namespace hexlod::grammar {

enum class ValueType : uint8_t { Number, Boolean };

// Appends the expression's code to `grammar` and returns its index in grammar.expressions,
// or nothing after reporting the error. `context` names the place for messages, for
// example "the height of Extrude".
std::optional<uint32_t> compileExpression(const ExprNode& node, ValueType expected,
                                          const std::string& context, CompiledGrammar& grammar,
                                          DiagnosticList& diagnostics);

// True for names that expressions resolve to accessors, constants or functions; parameters
// may not take them.
bool isReservedExpressionName(const std::string& name);

} // namespace hexlod::grammar
