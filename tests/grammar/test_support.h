// Shared helpers for grammar tests: compile a grammar from text, expand one footprint.
#pragma once

#include "hexlod/grammar/compiled_grammar.h"
#include "hexlod/grammar/expander.h"

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace hexlod::test {

// Compiles `source`; records a test failure with the diagnostics if it does not compile.
grammar::CompiledGrammar compileOrFail(std::string_view source, const std::string& fileName = "test.grammar");

// Compiles `source` and returns the formatted diagnostics ("" if it compiled cleanly).
std::string compileErrors(std::string_view source, const std::string& fileName = "test.grammar");

// Counter-clockwise w x d rectangle with its corner at `corner`.
std::vector<glm::dvec2> rectangle(double w, double d, glm::dvec2 corner = {0.0, 0.0});

struct Expansion {
    grammar::BuildingOutput output;
    std::vector<grammar::Terminal> terminals; // decoded, in derivation order
};

// Expands one building with id `building` (seed 1, cell origin 0 unless given).
Expansion expandOne(const grammar::CompiledGrammar& g, const std::vector<glm::dvec2>& footprint,
                    const std::vector<grammar::ParameterOverride>& overrides = {}, uint32_t building = 0,
                    grammar::ExpansionSettings settings = {});

std::map<std::string, size_t> countByShape(const grammar::CompiledGrammar& g,
                                           const std::vector<grammar::Terminal>& terminals);

} // namespace hexlod::test
