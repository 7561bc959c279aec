// Micro-benchmarks of the grammar engine: compile time and rule expansion per building
// (thesis anchor: 0.2 ms per building on a GTX 480).
#include "hexlod/grammar/batch_expander.h"
#include "hexlod/scene/demo_footprints.h"

#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>

namespace {

using namespace hexlod;

std::string grammarPath(const char* name) {
    return std::string(HEXLOD_CONFIGS_DIR) + "/grammars/" + name + ".grammar";
}

grammar::CompiledGrammar load(const char* name) {
    grammar::DiagnosticList diagnostics;
    grammar::CompiledGrammar g = grammar::compileGrammarFile(grammarPath(name), diagnostics);
    if (diagnostics.hasErrors()) throw std::runtime_error(diagnostics.formatAll());
    return g;
}

void compileGrammarText(benchmark::State& state, const char* name) {
    std::ifstream in(grammarPath(name));
    std::stringstream text;
    text << in.rdbuf();
    const std::string source = text.str();
    for (auto _ : state) {
        grammar::DiagnosticList diagnostics;
        benchmark::DoNotOptimize(grammar::compileGrammar(source, name, diagnostics));
    }
}

// One building at a time on one thread, cycling through 256 demo footprints.
void expandBuilding(benchmark::State& state, const char* name) {
    const grammar::CompiledGrammar g = load(name);
    std::vector<grammar::BuildingInput> buildings = scene::makeDemoFootprints({256, 1, 60.0});
    for (grammar::BuildingInput& b : buildings) {
        grammar::DiagnosticList ignored;
        b.parameters = grammar::resolveParameters(g, scene::demoParameterOverrides(g, 1, b.id), ignored);
    }
    grammar::ExpansionSettings settings;
    settings.seed = 1;
    grammar::BuildingExpander expander(g, settings);
    grammar::BuildingOutput out;
    size_t i = 0, terminals = 0;
    for (auto _ : state) {
        expander.expand(buildings[i++ % buildings.size()], out);
        terminals += out.terminals.size();
        benchmark::DoNotOptimize(out.terminals.data());
    }
    state.counters["terminals/s"] = benchmark::Counter(double(terminals), benchmark::Counter::kIsRate);
    state.counters["terminals/building"] = double(terminals) / double(state.iterations());
}

BENCHMARK_CAPTURE(compileGrammarText, residential, "residential");
BENCHMARK_CAPTURE(compileGrammarText, business, "business");
BENCHMARK_CAPTURE(expandBuilding, thesis_example, "thesis-example")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(expandBuilding, residential, "residential")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(expandBuilding, business, "business")->Unit(benchmark::kMicrosecond);

} // namespace

BENCHMARK_MAIN();
