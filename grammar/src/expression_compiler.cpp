#include "expression_compiler.h"

#include <array>
#include <cstring>
#include <string_view>

namespace hexlod::grammar {
namespace {

struct AccessorName {
    const char* name;
    Accessor accessor;
};
constexpr AccessorName kAccessorNames[] = {
    {"width", Accessor::Width},
    {"height", Accessor::Height},
    {"size_z", Accessor::SizeZ},
    {"elevation", Accessor::Elevation},
    {"floor", Accessor::Floor},
    {"floor_count", Accessor::Floors},
    {"index", Accessor::Index},
    {"count", Accessor::Count},
    {"level", Accessor::Level},
    {"depth", Accessor::Depth},
    {"normal_x", Accessor::NormalX},
    {"normal_y", Accessor::NormalY},
    {"normal_z", Accessor::NormalZ},
    {"world_normal_x", Accessor::WorldNormalX},
    {"world_normal_y", Accessor::WorldNormalY},
    {"world_normal_z", Accessor::WorldNormalZ},
    {"atom", Accessor::Atom},
    {"atoms", Accessor::Atoms},
    {"building", Accessor::Building},
};
static_assert(std::size(kAccessorNames) == kAccessorCount);

struct FunctionName {
    const char* name;
    Opcode op;
    int arity;
};
constexpr FunctionName kFunctions[] = {
    {"min", Opcode::Min, 2},
    {"max", Opcode::Max, 2},
    {"abs", Opcode::Abs, 1},
    {"floor", Opcode::Floor, 1},
    {"ceil", Opcode::Ceil, 1},
    {"round", Opcode::Round, 1},
    {"sqrt", Opcode::Sqrt, 1},
    {"sin", Opcode::Sin, 1},
    {"cos", Opcode::Cos, 1},
    {"pow", Opcode::Pow, 2},
    {"clamp", Opcode::Clamp, 3},
    {"rand", Opcode::Random, 2},
    {"building_rand", Opcode::BuildingRandom, 1},
};

constexpr float kPi = 3.14159265358979323846f;

const char* typeName(ValueType type) {
    return type == ValueType::Number ? "a number" : "a boolean";
}

class ExpressionCompiler {
public:
    ExpressionCompiler(CompiledGrammar& grammar, DiagnosticList& diagnostics)
        : grammar_(grammar), diagnostics_(diagnostics) {}

    // Emits code for `node`; returns its type, or nothing after an error.
    std::optional<ValueType> emit(const ExprNode& node, int depth) {
        // `depth` is the stack slot this value will occupy, so the check is exact.
        if (depth >= kMaxEvaluationStack) return error(node, "expression is too complex to evaluate");
        switch (node.kind) {
        case ExprNode::Kind::Number:
            push(Opcode::PushConstant, static_cast<float>(node.number));
            return ValueType::Number;
        case ExprNode::Kind::Name:
            return emitName(node);
        case ExprNode::Kind::Unary:
            return emitUnary(node, depth);
        case ExprNode::Kind::Binary:
            return emitBinary(node, depth);
        case ExprNode::Kind::Ternary:
            return emitTernary(node, depth);
        case ExprNode::Kind::Call:
            return emitCall(node, depth);
        }
        return std::nullopt;
    }

    std::vector<Instruction> code;
    bool dependsOnInputs = false;

private:
    std::optional<ValueType> error(const ExprNode& node, const std::string& message) {
        diagnostics_.error(node.location, message);
        return std::nullopt;
    }
    void push(Opcode op, float value) {
        Instruction in{op, {}};
        in.operand.value = value;
        code.push_back(in);
    }
    void push(Opcode op, uint32_t index) {
        Instruction in{op, {}};
        in.operand.index = index;
        code.push_back(in);
    }

    std::optional<ValueType> emitName(const ExprNode& node) {
        const int param = grammar_.findParameter(node.name);
        if (param >= 0) {
            push(Opcode::LoadParam, static_cast<uint32_t>(param));
            dependsOnInputs = true;
            return ValueType::Number;
        }
        for (const AccessorName& accessor : kAccessorNames) {
            if (node.name == accessor.name) {
                push(Opcode::LoadAccessor, static_cast<uint32_t>(accessor.accessor));
                dependsOnInputs = true;
                return ValueType::Number;
            }
        }
        if (node.name == "pi") {
            push(Opcode::PushConstant, kPi);
            return ValueType::Number;
        }
        if (node.name == "true" || node.name == "false") {
            push(Opcode::PushConstant, node.name == "true" ? 1.0f : 0.0f);
            return ValueType::Boolean;
        }
        if (grammar_.findRule(node.name) >= 0 || grammar_.findShape(node.name) >= 0) {
            return error(node, "'" + node.name + "' names a rule or shape, not a value");
        }
        return error(node, "unknown parameter or accessor '" + node.name + "'");
    }

    std::optional<ValueType> expectType(const ExprNode& node, int depth, ValueType expected,
                                        const char* what) {
        const std::optional<ValueType> type = emit(node, depth);
        if (!type) return std::nullopt;
        if (*type != expected) {
            return error(node, std::string("type error: ") + what + " needs " + typeName(expected) +
                                   ", found " + typeName(*type));
        }
        return type;
    }

    std::optional<ValueType> emitUnary(const ExprNode& node, int depth) {
        const bool isNot = node.op == TokenKind::Bang;
        const ValueType operand = isNot ? ValueType::Boolean : ValueType::Number;
        if (!expectType(*node.children[0], depth, operand, isNot ? "'!'" : "unary '-'")) return std::nullopt;
        push(isNot ? Opcode::Not : Opcode::Negate, 0.0f);
        return operand;
    }

    std::optional<ValueType> emitBinary(const ExprNode& node, int depth) {
        Opcode op = Opcode::Add;
        ValueType operand = ValueType::Number, result = ValueType::Number;
        switch (node.op) {
        case TokenKind::Plus:
            op = Opcode::Add;
            break;
        case TokenKind::Minus:
            op = Opcode::Subtract;
            break;
        case TokenKind::Star:
            op = Opcode::Multiply;
            break;
        case TokenKind::Slash:
            op = Opcode::Divide;
            break;
        case TokenKind::Percent:
            op = Opcode::Modulo;
            break;
        case TokenKind::Less:
            op = Opcode::Less, result = ValueType::Boolean;
            break;
        case TokenKind::LessEqual:
            op = Opcode::LessEqual, result = ValueType::Boolean;
            break;
        case TokenKind::Greater:
            op = Opcode::Greater, result = ValueType::Boolean;
            break;
        case TokenKind::GreaterEqual:
            op = Opcode::GreaterEqual, result = ValueType::Boolean;
            break;
        case TokenKind::AndAnd:
            op = Opcode::And, operand = result = ValueType::Boolean;
            break;
        case TokenKind::OrOr:
            op = Opcode::Or, operand = result = ValueType::Boolean;
            break;
        case TokenKind::EqualEqual:
        case TokenKind::NotEqual: {
            // Equality compares two values of the same type, numbers or booleans.
            const std::optional<ValueType> left = emit(*node.children[0], depth);
            if (!left) return std::nullopt;
            const char* what =
                node.op == TokenKind::EqualEqual ? "the right side of '=='" : "the right side of '!='";
            if (!expectType(*node.children[1], depth + 1, *left, what)) return std::nullopt;
            push(node.op == TokenKind::EqualEqual ? Opcode::Equal : Opcode::NotEqual, 0.0f);
            return ValueType::Boolean;
        }
        default:
            return error(node, "unsupported operator");
        }
        const std::string operatorName = std::string("operator ") + tokenKindName(node.op);
        if (!expectType(*node.children[0], depth, operand, operatorName.c_str())) return std::nullopt;
        if (!expectType(*node.children[1], depth + 1, operand, operatorName.c_str())) return std::nullopt;
        push(op, 0.0f);
        return result;
    }

    std::optional<ValueType> emitTernary(const ExprNode& node, int depth) {
        if (!expectType(*node.children[0], depth, ValueType::Boolean, "the condition of '?:'"))
            return std::nullopt;
        const std::optional<ValueType> whenTrue = emit(*node.children[1], depth + 1);
        if (!whenTrue) return std::nullopt;
        if (!expectType(*node.children[2], depth + 2, *whenTrue, "the second branch of '?:'"))
            return std::nullopt;
        push(Opcode::Select, 0.0f);
        return whenTrue;
    }

    std::optional<ValueType> emitCall(const ExprNode& node, int depth) {
        for (const FunctionName& function : kFunctions) {
            if (node.name != function.name) continue;
            if (static_cast<int>(node.children.size()) != function.arity) {
                return error(node, "function '" + node.name + "' takes " + std::to_string(function.arity) +
                                       " argument(s), found " + std::to_string(node.children.size()));
            }
            for (size_t i = 0; i < node.children.size(); ++i) {
                const std::string what = "argument " + std::to_string(i + 1) + " of " + node.name + "()";
                if (!expectType(*node.children[i], depth + static_cast<int>(i), ValueType::Number,
                                what.c_str())) {
                    return std::nullopt;
                }
            }
            if (function.op == Opcode::Random || function.op == Opcode::BuildingRandom)
                dependsOnInputs = true;
            push(function.op, 0.0f);
            return ValueType::Number;
        }
        return error(node, "unknown function '" + node.name + "'");
    }

    CompiledGrammar& grammar_;
    DiagnosticList& diagnostics_;
};

} // namespace

bool isReservedExpressionName(const std::string& name) {
    for (const AccessorName& accessor : kAccessorNames) {
        if (name == accessor.name) return true;
    }
    for (const FunctionName& function : kFunctions) {
        if (name == function.name) return true;
    }
    return name == "pi" || name == "true" || name == "false";
}

std::optional<uint32_t> compileExpression(const ExprNode& node, ValueType expected,
                                          const std::string& context, CompiledGrammar& grammar,
                                          DiagnosticList& diagnostics) {
    ExpressionCompiler compiler(grammar, diagnostics);
    const std::optional<ValueType> type = compiler.emit(node, 0);
    if (!type) return std::nullopt;
    if (*type != expected) {
        diagnostics.error(node.location, "type error: " + context + " needs " + typeName(expected) +
                                             ", found " + typeName(*type));
        return std::nullopt;
    }
    Expression expression;
    expression.isBoolean = expected == ValueType::Boolean;
    if (!compiler.dependsOnInputs) {
        // Folding keeps constant sizes off the hot path: the expander reads constantValue.
        expression.isConstant = true;
        expression.constantValue =
            evaluate(compiler.code.data(), static_cast<uint32_t>(compiler.code.size()), {});
        compiler.code.clear();
        compiler.code.push_back({Opcode::PushConstant, {}});
        compiler.code.back().operand.value = expression.constantValue;
    }
    expression.first = static_cast<uint32_t>(grammar.code.size());
    expression.count = static_cast<uint32_t>(compiler.code.size());
    grammar.code.insert(grammar.code.end(), compiler.code.begin(), compiler.code.end());
    grammar.expressions.push_back(expression);
    return static_cast<uint32_t>(grammar.expressions.size() - 1);
}

} // namespace hexlod::grammar
