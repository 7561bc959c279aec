#include "expression_compiler.h"
#include "hexlod/grammar/compiled_grammar.h"
#include "hexlod/grammar/parser.h"
#include "hexlod/grammar/rule_reachability.h"
#include "rule_lowering.h"
#include "termination_check.h"

#include <cmath>
#include <deque>
#include <unordered_set>

namespace hexlod::grammar {
namespace {

void compileParameters(const GrammarAst& ast, CompiledGrammar& grammar, DiagnosticList& diagnostics) {
    std::unordered_map<std::string, SourceLocation> seen;
    for (const ParamDecl& param : ast.params) {
        const auto [it, inserted] = seen.emplace(param.name, param.location);
        if (!inserted) {
            diagnostics.error(param.location, "parameter '" + param.name +
                                                  "' is declared twice (first at line " +
                                                  std::to_string(it->second.line) + ")");
            continue;
        }
        if (isReservedExpressionName(param.name)) {
            diagnostics.error(param.location, "parameter '" + param.name +
                                                  "' would hide the accessor or function of "
                                                  "that name; choose another name");
            continue;
        }
        if (!(param.minValue <= param.maxValue)) {
            diagnostics.error(param.location, "parameter '" + param.name + "' has an empty range");
            continue;
        }
        if (!(param.defaultValue >= param.minValue && param.defaultValue <= param.maxValue)) {
            diagnostics.error(param.location,
                              "the default of parameter '" + param.name + "' lies outside its range");
            continue;
        }
        grammar.params.push_back({param.name, static_cast<float>(param.defaultValue),
                                  static_cast<float>(param.minValue), static_cast<float>(param.maxValue)});
    }
}

bool applyShapeField(const ShapeField& field, ShapeInfo& shape, DiagnosticList& diagnostics) {
    auto require = [&](bool ok, const char* rule) {
        if (!ok) diagnostics.error(field.location, "shape field '" + field.name + "' must be " + rule);
        return ok;
    };
    const double v = field.value;
    if (field.name == "width")
        return require(v > 0 && v < 1e5, "in (0, 1e5) metres") && (shape.width = float(v), true);
    if (field.name == "height")
        return require(v > 0 && v < 1e5, "in (0, 1e5) metres") && (shape.height = float(v), true);
    if (field.name == "depth")
        return require(v >= 0 && v < 1e5, "in [0, 1e5) metres") && (shape.depth = float(v), true);
    if (field.name == "depth_ratio") {
        return require(v >= 0 && v <= 10, "in [0, 10]") && (shape.depthRatio = float(v), true);
    }
    if (field.name == "triangles") {
        return require(v >= 1 && v <= 1e6 && std::floor(v) == v, "a whole number in [1, 1e6]") &&
               (shape.triangles = uint32_t(v), true);
    }
    diagnostics.error(field.location, "unknown shape field '" + field.name +
                                          "' (expected width, height, depth, depth_ratio or triangles)");
    return false;
}

void compileShapes(const GrammarAst& ast, CompiledGrammar& grammar, DiagnosticList& diagnostics) {
    for (const ShapeDeclAst& decl : ast.shapes) {
        if (grammar.findShape(decl.name) >= 0) {
            diagnostics.error(decl.location, "shape '" + decl.name + "' is declared twice");
            continue;
        }
        if (grammar.shapes.size() >= 0xffff) {
            diagnostics.error(decl.location, "too many shapes (at most 65535)");
            return;
        }
        ShapeInfo shape;
        shape.name = decl.name;
        bool ok = true;
        bool hasTriangles = false;
        for (const ShapeField& field : decl.fields) {
            ok = applyShapeField(field, shape, diagnostics) && ok;
            hasTriangles = hasTriangles || field.name == "triangles";
        }
        if (!hasTriangles) {
            diagnostics.error(decl.location,
                              "shape '" + decl.name + "' needs a triangle count (triangles = N)");
            ok = false;
        }
        if (ok) grammar.shapes.push_back(shape);
    }
}

// Without an extruded_set directive the extruded set stops after the first growth rule
// (Extrude) met in breadth-first order from the axiom.
void markDefaultExtrudedStops(CompiledGrammar& grammar) {
    std::vector<bool> visited(grammar.rules.size(), false);
    std::deque<uint32_t> queue{grammar.axiom};
    visited[grammar.axiom] = true;
    while (!queue.empty()) {
        const CompiledRule& rule = grammar.rules[queue.front()];
        queue.pop_front();
        for (uint32_t s = 0; s < rule.successorCount; ++s) {
            const uint32_t successor = grammar.successors[rule.firstSuccessor + s];
            if (rule.op == RuleOp::Extrude) {
                if (successor != kNullRule) grammar.rules[successor].extrudedStop = true;
            } else if (successor != kNullRule && !visited[successor]) {
                visited[successor] = true;
                queue.push_back(successor);
            }
        }
        if (rule.op == RuleOp::Extrude) return;
    }
}

void warnUnreachable(const CompiledGrammar& grammar, DiagnosticList& diagnostics) {
    const std::vector<bool> reached = reachableRules(grammar);
    for (uint32_t r = 0; r < grammar.rules.size(); ++r) {
        if (!reached[r]) {
            diagnostics.warning(grammar.ruleLocations[r], "rule '" + grammar.ruleNames[r] +
                                                              "' is never reached from the axiom '" +
                                                              grammar.ruleNames[grammar.axiom] + "'");
        }
    }
}

uint64_t hashBytes(uint64_t hash, const void* data, size_t size);

// Declared but never emitted or read: worth a warning, since a scene bakes impostors only
// for shapes its grammars emit and a parameter nobody reads is usually a typo elsewhere.
void warnUnused(const GrammarAst& ast, const CompiledGrammar& grammar, DiagnosticList& diagnostics) {
    std::vector<bool> shapeUsed(grammar.shapes.size(), false), paramUsed(grammar.params.size(), false);
    for (const CompiledRule& rule : grammar.rules) {
        if (rule.op == RuleOp::Shape) shapeUsed[rule.shape] = true;
    }
    for (const Instruction& in : grammar.code) {
        if (in.op == Opcode::LoadParam) paramUsed[in.operand.index] = true;
    }
    for (const ParamDecl& param : ast.params) {
        const int index = grammar.findParameter(param.name);
        // wall_material is read by the extruded set (LOD0), not by rules.
        if (index >= 0 && !paramUsed[index] && param.name != "wall_material") {
            diagnostics.warning(param.location, "parameter '" + param.name + "' is declared but never read");
        }
    }
    for (const ShapeDeclAst& shape : ast.shapes) {
        const int index = grammar.findShape(shape.name);
        if (index >= 0 && !shapeUsed[index]) {
            diagnostics.warning(shape.location,
                                "shape '" + shape.name + "' is declared but no rule emits it");
        }
    }
}

uint64_t hashBytes(uint64_t hash, const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 0x100000001b3ull; // FNV-1a
    return hash;
}
template <typename T> uint64_t hashValue(uint64_t hash, const T& value) {
    return hashBytes(hash, &value, sizeof(T));
}
uint64_t hashString(uint64_t hash, const std::string& s) {
    return hashBytes(hashValue(hash, s.size()), s.data(), s.size());
}

// The content hash feeds cache keys: it covers everything that changes expansion output.
uint64_t contentHash(const CompiledGrammar& g) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (const CompiledRule& r : g.rules) {
        h = hashValue(h, r.key);
        const uint32_t fields[] = {uint32_t(r.op),   uint32_t(r.axis),  uint32_t(r.secondAxis),
                                   uint32_t(r.mode), uint32_t(r.pivot), uint32_t(r.extrudedStop),
                                   r.shape,          r.firstArgument,   r.argumentCount,
                                   r.firstSuccessor, r.successorCount};
        h = hashBytes(h, fields, sizeof(fields));
    }
    for (const RuleArgumentRef& a : g.arguments)
        h = hashValue(hashValue(h, a.expression), uint8_t(a.relative));
    h = hashBytes(h, g.successors.data(), g.successors.size() * sizeof(uint32_t));
    for (const Expression& e : g.expressions) {
        const uint32_t fields[] = {e.first, e.count, uint32_t(e.isBoolean), uint32_t(e.isConstant)};
        h = hashValue(hashBytes(h, fields, sizeof(fields)), e.constantValue);
    }
    for (const Instruction& in : g.code) h = hashValue(hashValue(h, uint8_t(in.op)), in.operand.index);
    for (const ParameterInfo& p : g.params) {
        h = hashValue(hashValue(hashValue(hashString(h, p.name), p.defaultValue), p.minValue), p.maxValue);
    }
    for (const ShapeInfo& s : g.shapes) {
        const float dims[] = {s.width, s.height, s.depth, s.depthRatio};
        h = hashValue(hashBytes(hashString(h, s.name), dims, sizeof(dims)), s.triangles);
    }
    return hashValue(h, g.axiom);
}

} // namespace

CompiledGrammar compileGrammar(std::string_view source, const std::string& fileName,
                               DiagnosticList& diagnostics) {
    const GrammarAst ast = parseGrammar(source, fileName, diagnostics);
    if (diagnostics.hasErrors()) return {};

    CompiledGrammar grammar;
    grammar.name = fileName;
    compileParameters(ast, grammar, diagnostics);
    compileShapes(ast, grammar, diagnostics);

    RuleIndexMap ruleIndex;
    for (const RuleDecl& rule : ast.rules) {
        const auto [it, inserted] =
            ruleIndex.emplace(rule.name, static_cast<uint32_t>(grammar.ruleNames.size()));
        if (!inserted) {
            diagnostics.error(rule.location, "rule '" + rule.name + "' is defined twice (first at line " +
                                                 std::to_string(grammar.ruleLocations[it->second].line) +
                                                 ")");
            continue;
        }
        if (rule.name == "NULL")
            diagnostics.error(rule.location, "'NULL' is reserved and cannot name a rule");
        grammar.ruleNames.push_back(rule.name);
        grammar.ruleLocations.push_back(rule.location);
    }
    if (ast.rules.empty()) diagnostics.error({fileName, 1, 1}, "the grammar has no rules");
    if (diagnostics.hasErrors()) return {};

    grammar.rules.resize(grammar.ruleNames.size());
    for (const RuleDecl& rule : ast.rules) {
        lowerRule(rule, ruleIndex, grammar, grammar.rules[ruleIndex.at(rule.name)], diagnostics);
    }
    if (diagnostics.hasErrors()) return {};

    if (ast.hasExtrudedDirective) {
        for (const SuccessorRef& stop : ast.extrudedStops) {
            const auto it = ruleIndex.find(stop.name);
            if (it == ruleIndex.end()) {
                diagnostics.error(stop.location, "extruded_set names unknown rule '" + stop.name + "'");
            } else {
                grammar.rules[it->second].extrudedStop = true;
            }
        }
    } else {
        markDefaultExtrudedStops(grammar);
    }
    checkTermination(grammar, diagnostics);
    if (diagnostics.hasErrors()) return {};
    warnUnreachable(grammar, diagnostics);
    warnUnused(ast, grammar, diagnostics);
    for (uint32_t r = 0; r < grammar.rules.size(); ++r) {
        const std::string& name = grammar.ruleNames[r];
        grammar.rules[r].key = hashBytes(0xcbf29ce484222325ull, name.data(), name.size());
    }
    grammar.contentHash = contentHash(grammar);
    return grammar;
}

} // namespace hexlod::grammar
