#include "rule_lowering.h"

#include "expression_compiler.h"

#include <cmath>

namespace hexlod::grammar {
namespace {

struct OperationSpec {
    const char* name;
    RuleOp op;
};
constexpr OperationSpec kOperations[] = {
    {"Extrude", RuleOp::Extrude}, {"Split", RuleOp::Split},         {"Repeat", RuleOp::Repeat},
    {"Branch", RuleOp::Branch},   {"Translate", RuleOp::Translate}, {"Rotate", RuleOp::Rotate},
    {"Cond", RuleOp::Cond},       {"Shape", RuleOp::Shape},         {"Explode", RuleOp::Explode},
    {"Project", RuleOp::Project}, {"Choose", RuleOp::Choose},       {"NULL", RuleOp::Null},
};

class RuleLowering {
public:
    RuleLowering(const RuleDecl& decl, const RuleIndexMap& rules, CompiledGrammar& grammar, CompiledRule& out,
                 DiagnosticList& diagnostics)
        : decl_(decl), rules_(rules), grammar_(grammar), out_(out), diagnostics_(diagnostics) {}

    bool run() {
        const OperationSpec* spec = nullptr;
        for (const OperationSpec& candidate : kOperations) {
            if (decl_.operation == candidate.name) spec = &candidate;
        }
        if (!spec) {
            return fail(decl_.operationLocation,
                        "unknown rule operation '" + decl_.operation +
                            "' (expected Extrude, Split, Repeat, Branch, Translate, "
                            "Rotate, Cond, Shape, Explode, Project, Choose or NULL)");
        }
        out_.op = spec->op;
        out_.firstArgument = static_cast<uint32_t>(grammar_.arguments.size());
        out_.firstSuccessor = static_cast<uint32_t>(grammar_.successors.size());
        switch (spec->op) {
        case RuleOp::Extrude:
            return extrude();
        case RuleOp::Split:
            return split();
        case RuleOp::Repeat:
            return repeat();
        case RuleOp::Branch:
            return branch();
        case RuleOp::Translate:
            return numbers(3, 3, "Translate(x, y, z)") && successors(1, 1);
        case RuleOp::Rotate:
            return rotate();
        case RuleOp::Cond:
            return cond();
        case RuleOp::Shape:
            return shape();
        case RuleOp::Explode:
            return numbers(0, 0, "Explode()") && successors(5, 5);
        case RuleOp::Project:
            return project();
        case RuleOp::Choose:
            return choose();
        case RuleOp::Null:
            return numbers(0, 0, "NULL") && noSuccessors();
        }
        return false;
    }

private:
    bool fail(const SourceLocation& where, const std::string& message) {
        diagnostics_.error(where, message);
        return false;
    }
    std::string op() const { return decl_.operation; }

    bool arity(size_t minimum, size_t maximum, const char* signature) {
        const size_t n = decl_.arguments.size();
        if (n < minimum || n > maximum) {
            std::string expected = minimum == maximum
                                       ? std::to_string(minimum)
                                       : std::to_string(minimum) + " to " + std::to_string(maximum);
            return fail(decl_.operationLocation, "wrong number of arguments to " + op() + ": expected " +
                                                     expected + ", found " + std::to_string(n) +
                                                     " (usage: " + signature + ")");
        }
        return true;
    }

    bool plain(const RuleArgument& argument) {
        if (argument.relative) return fail(argument.relativeLocation, "'~' sizes are only allowed in Split");
        if (!argument.label.empty()) {
            return fail(argument.labelLocation, "':' successors are only allowed in Choose");
        }
        return true;
    }

    bool number(const RuleArgument& argument, const std::string& context, bool relative = false) {
        if (!relative && !plain(argument)) return false;
        const std::optional<uint32_t> expression =
            compileExpression(*argument.value, ValueType::Number, context, grammar_, diagnostics_);
        if (!expression) return false;
        grammar_.arguments.push_back({*expression, argument.relative});
        ++out_.argumentCount;
        return true;
    }

    bool numbers(size_t minimum, size_t maximum, const char* signature) {
        if (!arity(minimum, maximum, signature)) return false;
        for (size_t i = 0; i < decl_.arguments.size(); ++i) {
            if (!number(decl_.arguments[i], "argument " + std::to_string(i + 1) + " of " + op()))
                return false;
        }
        return true;
    }

    // A bare keyword argument such as `x`, `fit` or `center`; returns its index in `choices`.
    bool keyword(const RuleArgument& argument, std::initializer_list<const char*> choices, const char* what,
                 int& picked) {
        if (!plain(argument)) return false;
        const ExprNode& node = *argument.value;
        if (node.kind == ExprNode::Kind::Name) {
            int i = 0;
            for (const char* choice : choices) {
                if (node.name == choice) {
                    picked = i;
                    return true;
                }
                ++i;
            }
        }
        std::string list;
        for (const char* choice : choices) list += (list.empty() ? "" : "|") + std::string(choice);
        return fail(node.location, std::string("expected ") + what + " (" + list + ") in " + op());
    }

    bool axis(const RuleArgument& argument, Axis& result) {
        int picked = 0;
        if (!keyword(argument, {"x", "y", "z"}, "an axis", picked)) return false;
        result = static_cast<Axis>(picked);
        return true;
    }

    bool resolve(const SuccessorRef& ref, uint32_t& index) {
        if (ref.name == "NULL") {
            index = kNullRule;
            return true;
        }
        const auto it = rules_.find(ref.name);
        if (it == rules_.end()) {
            return fail(ref.location, "undefined successor '" + ref.name + "' in rule '" + decl_.name + "'");
        }
        index = it->second;
        return true;
    }

    bool successors(size_t minimum, size_t maximum) {
        const size_t n = decl_.successors.size();
        if (!decl_.hasSuccessorBlock || n < minimum || n > maximum) {
            std::string expected = minimum == maximum
                                       ? std::to_string(minimum)
                                       : std::to_string(minimum) + " to " + std::to_string(maximum);
            return fail(decl_.operationLocation, "wrong number of successors for " + op() + ": expected " +
                                                     expected + " in { }, found " + std::to_string(n));
        }
        for (const SuccessorRef& ref : decl_.successors) {
            uint32_t index = 0;
            if (!resolve(ref, index)) return false;
            grammar_.successors.push_back(index);
            ++out_.successorCount;
        }
        return true;
    }

    bool noSuccessors() {
        if (decl_.hasSuccessorBlock) {
            return fail(decl_.operationLocation, op() + " takes no successors; remove the { } block");
        }
        return true;
    }

    bool extrude() {
        return numbers(1, 3, "Extrude(height[, scale, twist]) {side, top}") && successors(2, 2);
    }

    bool split() {
        if (decl_.arguments.size() < 2 || decl_.arguments.size() > kMaxSplitParts + 1) {
            return arity(2, kMaxSplitParts + 1, "Split(x|y|z, size1, ~relative2, ...) {A, B, ...}");
        }
        if (!axis(decl_.arguments[0], out_.axis)) return false;
        for (size_t i = 1; i < decl_.arguments.size(); ++i) {
            const RuleArgument& argument = decl_.arguments[i];
            if (!argument.label.empty()) return plain(argument);
            if (!number(argument, "size " + std::to_string(i) + " of Split", true)) return false;
        }
        const size_t sizes = decl_.arguments.size() - 1;
        return successors(sizes, sizes);
    }

    bool repeat() {
        if (!arity(3, 3, "Repeat(x|y|z, size, fit|equal) {Tile[, Margin]}")) return false;
        if (!axis(decl_.arguments[0], out_.axis)) return false;
        if (!number(decl_.arguments[1], "the tile size of Repeat")) return false;
        int mode = 0;
        if (!keyword(decl_.arguments[2], {"fit", "equal"}, "a repeat mode", mode)) return false;
        out_.mode = static_cast<RepeatMode>(mode);
        return successors(1, 2);
    }

    bool branch() {
        if (!numbers(1, 1, "Branch(n) {A} or Branch(n) {A1, ..., An}")) return false;
        const Expression& count = grammar_.expressions[grammar_.arguments[out_.firstArgument].expression];
        if (count.isConstant && count.constantValue >= 0.5f && count.constantValue < 1024.5f) {
            // Rounded as the expander rounds it, so Branch(2.6) checks for 3 successors.
            const size_t n = static_cast<size_t>(std::nearbyint(count.constantValue));
            const size_t given = decl_.successors.size();
            if (n > 1 && given == n) return successors(n, n);
            if (n > 1 && decl_.hasSuccessorBlock && given != 1) {
                return fail(decl_.operationLocation, "wrong number of successors for Branch: expected 1 or " +
                                                         std::to_string(n) + " in { }, found " +
                                                         std::to_string(given));
            }
        } else if (count.isConstant) {
            return fail(decl_.arguments[0].value->location, "Branch count must be between 1 and 1024");
        }
        return successors(1, 1);
    }

    bool rotate() {
        if (!arity(3, 3, "Rotate(origin|center, x|y|z, degrees) {A}")) return false;
        int pivot = 0;
        if (!keyword(decl_.arguments[0], {"origin", "center"}, "a pivot", pivot)) return false;
        out_.pivot = static_cast<Pivot>(pivot);
        if (!axis(decl_.arguments[1], out_.axis)) return false;
        return number(decl_.arguments[2], "the angle of Rotate") && successors(1, 1);
    }

    bool cond() {
        if (!arity(1, 1, "Cond(condition) {Then, Else}")) return false;
        if (!plain(decl_.arguments[0])) return false;
        const std::optional<uint32_t> expression = compileExpression(
            *decl_.arguments[0].value, ValueType::Boolean, "the condition of Cond", grammar_, diagnostics_);
        if (!expression) return false;
        grammar_.arguments.push_back({*expression, false});
        ++out_.argumentCount;
        return successors(1, 2);
    }

    bool shape() {
        if (!arity(1, 2, "Shape(name[, depthRatio])")) return false;
        const RuleArgument& name = decl_.arguments[0];
        if (!plain(name)) return false;
        if (name.value->kind != ExprNode::Kind::Name) {
            return fail(name.value->location, "expected a shape name as the first argument of Shape");
        }
        const int shape = grammar_.findShape(name.value->name);
        if (shape < 0) {
            return fail(name.value->location,
                        "unknown shape '" + name.value->name + "'; declare it with `shape " +
                            name.value->name +
                            "(width = ..., height = ..., depth = ..., depth_ratio = ..., triangles = ...);`");
        }
        out_.shape = static_cast<uint16_t>(shape);
        if (decl_.arguments.size() == 2 && !number(decl_.arguments[1], "the depth ratio of Shape"))
            return false;
        return noSuccessors();
    }

    bool project() {
        if (!arity(2, 2, "Project(x|y|z, x|y|z) {A}")) return false;
        if (!axis(decl_.arguments[0], out_.axis) || !axis(decl_.arguments[1], out_.secondAxis)) return false;
        if (out_.axis == out_.secondAxis) {
            return fail(decl_.arguments[1].value->location, "Project needs two different axes");
        }
        return successors(1, 1);
    }

    bool choose() {
        if (decl_.arguments.empty() || decl_.arguments.size() > kMaxSplitParts) {
            return arity(1, kMaxSplitParts, "Choose(p1: A, p2: B, ...)");
        }
        for (size_t i = 0; i < decl_.arguments.size(); ++i) {
            const RuleArgument& argument = decl_.arguments[i];
            if (argument.label.empty()) {
                return fail(argument.value->location, "Choose needs 'probability: Successor' pairs");
            }
            if (argument.relative)
                return fail(argument.relativeLocation, "'~' sizes are only allowed in Split");
            const std::optional<uint32_t> expression = compileExpression(
                *argument.value, ValueType::Number, "a probability of Choose", grammar_, diagnostics_);
            if (!expression) return false;
            const Expression& weight = grammar_.expressions[*expression];
            if (weight.isConstant && !(weight.constantValue >= 0.0f && std::isfinite(weight.constantValue))) {
                return fail(argument.value->location,
                            "a probability of Choose must be finite and not negative");
            }
            grammar_.arguments.push_back({*expression, false});
            ++out_.argumentCount;
            uint32_t index = 0;
            if (!resolve({argument.label, argument.labelLocation}, index)) return false;
            grammar_.successors.push_back(index);
            ++out_.successorCount;
        }
        return noSuccessors();
    }

    const RuleDecl& decl_;
    const RuleIndexMap& rules_;
    CompiledGrammar& grammar_;
    CompiledRule& out_;
    DiagnosticList& diagnostics_;
};

} // namespace

bool lowerRule(const RuleDecl& decl, const RuleIndexMap& rules, CompiledGrammar& grammar, CompiledRule& out,
               DiagnosticList& diagnostics) {
    return RuleLowering(decl, rules, grammar, out, diagnostics).run();
}

} // namespace hexlod::grammar
