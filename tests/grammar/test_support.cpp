#include "test_support.h"

#include <gtest/gtest.h>

namespace hexlod::test {

grammar::CompiledGrammar compileOrFail(std::string_view source, const std::string& fileName) {
    grammar::DiagnosticList diagnostics;
    grammar::CompiledGrammar g = grammar::compileGrammar(source, fileName, diagnostics);
    EXPECT_FALSE(diagnostics.hasErrors()) << diagnostics.formatAll();
    return g;
}

std::string compileErrors(std::string_view source, const std::string& fileName) {
    grammar::DiagnosticList diagnostics;
    grammar::compileGrammar(source, fileName, diagnostics);
    return diagnostics.formatAll();
}

std::vector<glm::dvec2> rectangle(double w, double d, glm::dvec2 corner) {
    return {corner, corner + glm::dvec2(w, 0), corner + glm::dvec2(w, d), corner + glm::dvec2(0, d)};
}

Expansion expandOne(const grammar::CompiledGrammar& g, const std::vector<glm::dvec2>& footprint,
                    const std::vector<grammar::ParameterOverride>& overrides, uint32_t building,
                    grammar::ExpansionSettings settings) {
    if (settings.seed == 0) settings.seed = 1;
    grammar::DiagnosticList diagnostics;
    grammar::BuildingInput input;
    input.id = building;
    input.footprint = footprint;
    input.parameters = grammar::resolveParameters(g, overrides, diagnostics);
    EXPECT_FALSE(diagnostics.hasErrors()) << diagnostics.formatAll();
    grammar::BuildingExpander expander(g, settings);
    Expansion result;
    expander.expand(input, result.output);
    for (const grammar::TerminalRecord& record : result.output.terminals) {
        result.terminals.push_back(grammar::unpackTerminal(record));
    }
    return result;
}

std::map<std::string, size_t> countByShape(const grammar::CompiledGrammar& g,
                                           const std::vector<grammar::Terminal>& terminals) {
    std::map<std::string, size_t> counts;
    for (const grammar::Terminal& t : terminals) ++counts[g.shapes.at(t.shape).name];
    return counts;
}

} // namespace hexlod::test
