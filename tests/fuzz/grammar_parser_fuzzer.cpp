// libFuzzer target for the grammar front end and the expander: every input is compiled as
// a grammar and, if it compiles, one small building is expanded with it. Tight expansion
// limits keep each input to a few milliseconds, so the fuzzer spends its time on the
// lexer, parser, checker and rule code rather than on legitimately huge derivations.
#include "fuzz_check.h"

#include "hexlod/grammar/compiled_grammar.h"
#include "hexlod/grammar/expander.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

namespace {

using namespace hexlod::grammar;

using hexlod::fuzz::check;

void checkCompiled(const CompiledGrammar& g) {
    check(!g.rules.empty());
    check(g.axiom < g.rules.size());
    check(g.ruleNames.size() == g.rules.size() && g.ruleLocations.size() == g.rules.size());
    for (const CompiledRule& rule : g.rules) {
        check(uint64_t(rule.firstArgument) + rule.argumentCount <= g.arguments.size());
        check(uint64_t(rule.firstSuccessor) + rule.successorCount <= g.successors.size());
        if (rule.op == RuleOp::Shape) check(rule.shape < g.shapes.size());
    }
    for (const uint32_t successor : g.successors) check(successor == kNullRule || successor < g.rules.size());
    for (const RuleArgumentRef& argument : g.arguments) check(argument.expression < g.expressions.size());
    for (const Expression& e : g.expressions) {
        check(e.count > 0 && uint64_t(e.first) + e.count <= g.code.size());
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view source(reinterpret_cast<const char*>(data), size);
    DiagnosticList diagnostics;
    const CompiledGrammar g = compileGrammar(source, "fuzz.grammar", diagnostics);
    for (const Diagnostic& d : diagnostics.all()) {
        // Every diagnostic must point into the file: a user has to be able to find it.
        check(!formatDiagnostic(d).empty());
    }
    if (diagnostics.hasErrors()) {
        check(g.rules.empty()); // documented: on any error the grammar is empty
        return 0;
    }
    checkCompiled(g);

    // Compiling is a pure function of the text: the same input must give the same hash.
    DiagnosticList again;
    check(compileGrammar(source, "fuzz.grammar", again).contentHash == g.contentHash);

    ExpansionSettings settings;
    settings.seed = 1;
    settings.limits.maxDepth = 64;
    settings.limits.maxTerminalsPerAtom = 4096;
    settings.limits.maxOperationsPerAtom = 65536;
    BuildingInput building;
    building.id = 7;
    building.footprint = {{0.0, 0.0}, {12.0, 0.0}, {12.0, 8.0}, {0.0, 8.0}};
    building.parameters = g.defaultParameters();
    BuildingExpander expander(g, settings);
    BuildingOutput out;
    expander.expand(building, out);

    check(!out.skipped && out.atoms == 4);
    check(out.terminals.size() <= uint64_t(settings.limits.maxTerminalsPerAtom) * out.atoms);
    for (const TerminalRecord& record : out.terminals) {
        const Terminal t = unpackTerminal(record);
        check(t.shape < g.shapes.size() && t.building == building.id);
    }
    for (const ExpansionIssue& issue : out.issues) {
        check(issue.rule == kNullRule || issue.rule < g.rules.size());
        check(!describeIssue(g, issue).empty());
    }
    return 0;
}
