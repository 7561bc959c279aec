// Parse tree of a grammar file. The parser builds it; the compiler checks it and
// lowers it to the flat rule map, so nothing downstream ever sees this tree.
#pragma once

#include "hexlod/grammar/diagnostics.h"
#include "hexlod/grammar/lexer.h"

#include <memory>
#include <string>
#include <vector>

namespace hexlod::grammar {

struct ExprNode {
    enum class Kind : uint8_t { Number, Name, Unary, Binary, Ternary, Call };
    Kind kind = Kind::Number;
    double number = 0.0;
    std::string name; // Name and Call
    TokenKind op = TokenKind::End;
    std::vector<std::unique_ptr<ExprNode>> children;
    SourceLocation location;
};
using ExprPtr = std::unique_ptr<ExprNode>;

// One argument of a rule operation: `expr`, `~expr` (relative size) or `expr: Successor` (Choose).
struct RuleArgument {
    bool relative = false;
    SourceLocation relativeLocation; // of the '~'
    ExprPtr value;
    std::string label; // successor name after ':', empty if none
    SourceLocation labelLocation;
};

struct SuccessorRef {
    std::string name; // "NULL" for the empty successor
    SourceLocation location;
};

struct RuleDecl {
    std::string name;
    SourceLocation location;
    std::string operation;
    SourceLocation operationLocation;
    std::vector<RuleArgument> arguments;
    std::vector<SuccessorRef> successors;
    bool hasSuccessorBlock = false;
};

struct ParamDecl {
    std::string name;
    SourceLocation location;
    double defaultValue = 0.0;
    double minValue = 0.0;
    double maxValue = 0.0;
};

struct ShapeField {
    std::string name;
    double value = 0.0;
    SourceLocation location;
};

struct ShapeDeclAst {
    std::string name;
    SourceLocation location;
    std::vector<ShapeField> fields;
};

struct GrammarAst {
    std::string fileName;
    std::vector<ParamDecl> params;
    std::vector<ShapeDeclAst> shapes;
    std::vector<RuleDecl> rules;
    std::vector<SuccessorRef> extrudedStops; // from `extruded_set A, B;`
    bool hasExtrudedDirective = false;
};

} // namespace hexlod::grammar
