#include "hexlod/grammar/compiled_grammar.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace hexlod::grammar {

const char* ruleOpName(RuleOp op) {
    switch (op) {
    case RuleOp::Extrude:
        return "Extrude";
    case RuleOp::Split:
        return "Split";
    case RuleOp::Repeat:
        return "Repeat";
    case RuleOp::Branch:
        return "Branch";
    case RuleOp::Translate:
        return "Translate";
    case RuleOp::Rotate:
        return "Rotate";
    case RuleOp::Cond:
        return "Cond";
    case RuleOp::Shape:
        return "Shape";
    case RuleOp::Explode:
        return "Explode";
    case RuleOp::Project:
        return "Project";
    case RuleOp::Choose:
        return "Choose";
    case RuleOp::Null:
        return "NULL";
    }
    return "?";
}

namespace {
template <typename Items, typename Name>
int findByName(const Items& items, const std::string& wanted, Name name) {
    for (size_t i = 0; i < items.size(); ++i) {
        if (name(items[i]) == wanted) return static_cast<int>(i);
    }
    return -1;
}
} // namespace

int CompiledGrammar::findParameter(const std::string& parameterName) const {
    return findByName(params, parameterName,
                      [](const ParameterInfo& p) -> const std::string& { return p.name; });
}
int CompiledGrammar::findShape(const std::string& shapeName) const {
    return findByName(shapes, shapeName, [](const ShapeInfo& s) -> const std::string& { return s.name; });
}
int CompiledGrammar::findRule(const std::string& ruleName) const {
    return findByName(ruleNames, ruleName, [](const std::string& n) -> const std::string& { return n; });
}

std::vector<float> CompiledGrammar::defaultParameters() const {
    std::vector<float> values;
    values.reserve(params.size());
    for (const ParameterInfo& p : params) values.push_back(p.defaultValue);
    return values;
}

std::string CompiledGrammar::where(uint32_t rule) const {
    if (rule >= ruleNames.size()) return "rule #" + std::to_string(rule);
    const SourceLocation& at = ruleLocations[rule];
    return at.file + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) + ": rule '" +
           ruleNames[rule] + "'";
}

CompiledGrammar compileGrammarFile(const std::string& path, DiagnosticList& diagnostics) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        diagnostics.error({path, 0, 0}, "cannot open grammar file '" + path + "'");
        return {};
    }
    std::ostringstream text;
    text << in.rdbuf();
    return compileGrammar(text.str(), path, diagnostics);
}

std::vector<float> resolveParameters(const CompiledGrammar& grammar,
                                     const std::vector<ParameterOverride>& overrides,
                                     DiagnosticList& diagnostics) {
    std::vector<float> values = grammar.defaultParameters();
    for (const ParameterOverride& o : overrides) {
        const int index = grammar.findParameter(o.name);
        if (index < 0) {
            diagnostics.error({}, "unknown parameter '" + o.name + "' for grammar " + grammar.name);
            continue;
        }
        const ParameterInfo& info = grammar.params[index];
        if (!std::isfinite(o.value)) {
            diagnostics.error({}, "parameter '" + o.name + "' must be a finite number, got " +
                                      std::to_string(o.value));
            continue;
        }
        if (o.value < info.minValue || o.value > info.maxValue) {
            std::ostringstream message;
            message << "parameter '" << o.name << "' = " << o.value << " is outside its range ["
                    << info.minValue << ", " << info.maxValue << "]";
            diagnostics.error({}, message.str());
            continue;
        }
        values[index] = static_cast<float>(o.value);
    }
    return values;
}

} // namespace hexlod::grammar
