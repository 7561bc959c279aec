// Recursive-descent parser for the grammar language (docs/grammar.md).
#pragma once

#include "hexlod/grammar/ast.h"

#include <string_view>

namespace hexlod::grammar {

// Parses a whole grammar file. Errors are appended to `diagnostics` with file:line:col;
// the parser resynchronises at ';' so that one mistake does not hide the next.
GrammarAst parseGrammar(std::string_view source, const std::string& fileName, DiagnosticList& diagnostics);

} // namespace hexlod::grammar
