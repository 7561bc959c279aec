// Bytecode to GLSL: the stack machine is run symbolically, each value on it a GLSL
// expression, so the generated code is one nested expression per argument, the operations
// in the bytecode's order.
#include "hexlod/lod/lod1_codegen.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

namespace hexlod::lod {
namespace {

using grammar::Accessor;
using grammar::Opcode;

std::string floatLiteral(float v) {
    if (std::isnan(v)) return "uintBitsToFloat(0x7fc00000u)";
    if (std::isinf(v)) return v > 0 ? "uintBitsToFloat(0x7f800000u)" : "uintBitsToFloat(0xff800000u)";
    char text[40];
    // Nine significant digits round-trip every float exactly.
    std::snprintf(text, sizeof text, "%.9g", double(v));
    std::string s = text;
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return "float(" + s + ")";
}

std::string accessorGlsl(Accessor a) {
    switch (a) {
    case Accessor::Width:
        return "s.size.x";
    case Accessor::Height:
        return "s.size.y";
    case Accessor::SizeZ:
        return "0.0";
    case Accessor::Elevation:
        return "((c.origin + c.axisX * s.origin.x + c.axisY * s.origin.y).z - c.baseZ)";
    case Accessor::Floor:
        return "float(s.floor)";
    case Accessor::Floors:
        return "float(s.floors)";
    case Accessor::Index:
        return "float(s.index)";
    case Accessor::Count:
        return "float(s.count)";
    case Accessor::Level:
        return "float(s.level)";
    case Accessor::Depth:
        return "float(s.depth)";
    case Accessor::NormalX:
    case Accessor::WorldNormalX:
        return "c.normal.x";
    case Accessor::NormalY:
    case Accessor::WorldNormalY:
        return "c.normal.y";
    case Accessor::NormalZ:
    case Accessor::WorldNormalZ:
        return "c.normal.z";
    case Accessor::Atom:
        return "float(c.atom)";
    case Accessor::Atoms:
        return "float(c.atoms)";
    case Accessor::Building:
        return "float(c.building)";
    case Accessor::Count_:
        break;
    }
    return "0.0";
}

// The rules whose arguments lod1Walk evaluates: the 2D subdivisions of a face and the picks.
// Every other op ends the walk (or, Shape, needs no argument).
bool walkEvaluates(const grammar::CompiledRule& rule) {
    using grammar::RuleOp;
    const bool inFace = rule.axis != grammar::Axis::Z;
    return rule.op == RuleOp::Cond || rule.op == RuleOp::Choose ||
           ((rule.op == RuleOp::Split || rule.op == RuleOp::Repeat) && inFace);
}

} // namespace

std::string expressionToGlsl(const grammar::CompiledGrammar& g, const grammar::Expression& e) {
    if (e.isConstant) return floatLiteral(e.constantValue);
    std::vector<std::string> stack;
    auto pop = [&stack] {
        std::string top = std::move(stack.back());
        stack.pop_back();
        return top;
    };
    for (uint32_t pc = 0; pc < e.count; ++pc) {
        const grammar::Instruction& in = g.code[e.first + pc];
        switch (in.op) {
        case Opcode::PushConstant:
            stack.push_back(floatLiteral(in.operand.value));
            break;
        case Opcode::LoadParam:
            stack.push_back("lod1Parameter[" + std::to_string(in.operand.index) + "]");
            break;
        case Opcode::LoadAccessor:
            stack.push_back(accessorGlsl(Accessor(in.operand.index)));
            break;
        case Opcode::Negate:
            stack.back() = "(-" + stack.back() + ")";
            break;
        case Opcode::Not:
            stack.back() = "(" + stack.back() + " != 0.0 ? 0.0 : 1.0)";
            break;
        case Opcode::Abs:
            stack.back() = "abs(" + stack.back() + ")";
            break;
        case Opcode::Floor:
            stack.back() = "floor(" + stack.back() + ")";
            break;
        case Opcode::Ceil:
            stack.back() = "ceil(" + stack.back() + ")";
            break;
        case Opcode::Round:
            stack.back() = "roundEven(" + stack.back() + ")";
            break; // nearbyint
        case Opcode::Sqrt:
            stack.back() = "sqrt(" + stack.back() + ")";
            break;
        case Opcode::Sin:
            stack.back() = "sin(" + stack.back() + " * 0.0174532925)";
            break;
        case Opcode::Cos:
            stack.back() = "cos(" + stack.back() + " * 0.0174532925)";
            break;
        case Opcode::BuildingRandom:
            stack.back() =
                "lod1Unit(lod1Combine(c.buildingKey, doubleBitsToUint64(double(" + stack.back() + "))))";
            break;
        case Opcode::Select:
        case Opcode::Clamp: {
            const std::string c3 = pop(), b = pop(), a = pop();
            stack.push_back(in.op == Opcode::Select ? "(" + a + " != 0.0 ? " + b + " : " + c3 + ")"
                                                    : "min(max(" + a + ", " + b + "), " + c3 + ")");
            break;
        }
        default: {
            const std::string b = pop(), a = pop();
            auto binary = [&](const char* op) { return "(" + a + " " + op + " " + b + ")"; };
            auto compare = [&](const char* op) { return "(" + a + " " + op + " " + b + " ? 1.0 : 0.0)"; };
            std::string out;
            switch (in.op) {
            case Opcode::Add:
                out = binary("+");
                break;
            case Opcode::Subtract:
                out = binary("-");
                break;
            case Opcode::Multiply:
                out = binary("*");
                break;
            case Opcode::Divide:
                out = binary("/");
                break;
            // fmod, truncating like the CPU's, not GLSL's flooring mod().
            case Opcode::Modulo:
                out = "lod1Fmod(" + a + ", " + b + ")";
                break;
            case Opcode::Less:
                out = compare("<");
                break;
            case Opcode::LessEqual:
                out = compare("<=");
                break;
            case Opcode::Greater:
                out = compare(">");
                break;
            case Opcode::GreaterEqual:
                out = compare(">=");
                break;
            case Opcode::Equal:
                out = compare("==");
                break;
            case Opcode::NotEqual:
                out = compare("!=");
                break;
            case Opcode::And:
                out = "((" + a + " != 0.0 && " + b + " != 0.0) ? 1.0 : 0.0)";
                break;
            case Opcode::Or:
                out = "((" + a + " != 0.0 || " + b + " != 0.0) ? 1.0 : 0.0)";
                break;
            case Opcode::Min:
                out = "min(" + a + ", " + b + ")";
                break;
            case Opcode::Max:
                out = "max(" + a + ", " + b + ")";
                break;
            case Opcode::Pow:
                out = "pow(" + a + ", " + b + ")";
                break;
            case Opcode::Random:
                out = "(" + a + " + (" + b + " - " + a + ") * lod1Unit(lod1Combine(randomKey, " +
                      std::to_string(pc) + "ul)))";
                break;
            default:
                out = "0.0";
                break;
            }
            stack.push_back(out);
        }
        }
    }
    return stack.empty() ? "0.0" : stack.back();
}

std::string generateLod1Grammar(const grammar::CompiledGrammar& g) {
    std::ostringstream out;
    const size_t rules = std::max<size_t>(g.rules.size(), 1);
    out << "// Generated by lod1_codegen.cpp from grammar '" << g.name << "' (" << g.rules.size()
        << " rules).\n";
    out << "#define LOD1_RULES " << rules << "\n";
    // lod1Walk evaluates each argument of the rule it is at once, into an array this long;
    // lod1Argument has a case for those arguments only (it runs every case it has).
    std::vector<bool> evaluated(g.arguments.size(), false);
    uint32_t mostArguments = 1;
    for (const grammar::CompiledRule& rule : g.rules) {
        if (!walkEvaluates(rule)) continue;
        mostArguments = std::max(mostArguments, rule.argumentCount);
        for (uint32_t a = rule.firstArgument; a < rule.firstArgument + rule.argumentCount; ++a)
            if (a < evaluated.size()) evaluated[a] = true;
    }
    out << "#define LOD1_MAX_ARGUMENTS " << mostArguments << "\n";
    // op, axis, mode and successor count packed; argument and successor ranges; shape; key.
    auto table = [&](const char* name, const char* type, auto value, size_t count) {
        const std::string zero = std::string(type) == "uint64_t" ? "0ul" : "0u"; // GLSL arrays need an entry
        out << "const " << type << " " << name << "[" << std::max<size_t>(count, 1) << "] = " << type
            << "[](";
        for (size_t i = 0; i < std::max<size_t>(count, 1); ++i)
            out << (i ? ", " : "") << (i < count ? value(i) : zero);
        out << ");\n";
    };
    table(
        "lod1RuleOp", "uint",
        [&](size_t r) {
            const grammar::CompiledRule& rule = g.rules[r];
            return std::to_string(uint32_t(rule.op) | uint32_t(rule.axis) << 8 | uint32_t(rule.mode) << 12) +
                   "u";
        },
        g.rules.size());
    table(
        "lod1RuleArguments", "uint", [&](size_t r) { return std::to_string(g.rules[r].firstArgument) + "u"; },
        g.rules.size());
    table(
        "lod1RuleArgumentCount", "uint",
        [&](size_t r) { return std::to_string(g.rules[r].argumentCount) + "u"; }, g.rules.size());
    table(
        "lod1RuleSuccessors", "uint",
        [&](size_t r) { return std::to_string(g.rules[r].firstSuccessor) + "u"; }, g.rules.size());
    table(
        "lod1RuleSuccessorCount", "uint",
        [&](size_t r) { return std::to_string(g.rules[r].successorCount) + "u"; }, g.rules.size());
    table(
        "lod1RuleShape", "uint", [&](size_t r) { return std::to_string(g.rules[r].shape) + "u"; },
        g.rules.size());
    table(
        "lod1RuleKey", "uint64_t",
        [&](size_t r) {
            char text[32];
            std::snprintf(text, sizeof text, "0x%016" PRIx64 "ul", g.rules[r].key);
            return std::string(text);
        },
        g.rules.size());
    table(
        "lod1Successors", "uint", [&](size_t i) { return std::to_string(g.successors[i]) + "u"; },
        g.successors.size());
    table(
        "lod1ArgumentRelative", "uint",
        [&](size_t i) { return std::string(g.arguments[i].relative ? "1u" : "0u"); }, g.arguments.size());
    // The parameters the expressions read, loaded once per pixel: llvmpipe runs every case of
    // lod1Argument's switch for every argument it evaluates (masked, not branched around), so
    // a storage-buffer read in a case is paid that often; a private array read at a constant
    // index is a register.
    std::vector<bool> read(g.params.size(), false);
    for (size_t a = 0; a < g.arguments.size(); ++a) {
        if (!evaluated[a]) continue;
        const grammar::Expression& e = g.expressions[g.arguments[a].expression];
        for (uint32_t pc = 0; !e.isConstant && pc < e.count; ++pc) {
            const grammar::Instruction& in = g.code[e.first + pc];
            if (in.op == Opcode::LoadParam && in.operand.index < read.size()) read[in.operand.index] = true;
        }
    }
    out << "float lod1Parameter[" << std::max<size_t>(g.params.size(), 1) << "];\n";
    out << "void lod1LoadParameters(uint first) {\n";
    for (size_t p = 0; p < read.size(); ++p)
        if (read[p]) out << "    lod1Parameter[" << p << "] = lod1Params[first + " << p << "u];\n";
    out << "}\n";
    out << "float lod1Argument(uint argument, Lod1Scope s, Lod1Context c, uint64_t randomKey) {\n    switch "
           "(argument) {\n";
    for (size_t a = 0; a < g.arguments.size(); ++a) {
        if (!evaluated[a]) continue;
        out << "    case " << a << "u: return "
            << expressionToGlsl(g, g.expressions[g.arguments[a].expression]) << ";\n";
    }
    out << "    }\n    return 0.0;\n}\n";
    return out.str();
}

} // namespace hexlod::lod
