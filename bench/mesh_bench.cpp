// Terminal mesh library build time: every procedural mesh of the four shipped grammars
// (docs/BENCHMARKS.md, "Terminal meshes"), and the per-shape table of triangles and bytes.
#include "hexlod/render/terminal_mesh_library.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace {

using namespace hexlod;

std::vector<grammar::CompiledGrammar> shippedGrammars() {
    std::vector<grammar::CompiledGrammar> grammars;
    for (const char* name : {"residential", "business", "thesis-example", "tree"}) {
        grammar::DiagnosticList diagnostics;
        grammars.push_back(grammar::compileGrammarFile(
            std::string(HEXLOD_CONFIGS_DIR) + "/grammars/" + name + ".grammar", diagnostics));
        if (diagnostics.hasErrors()) throw std::runtime_error(diagnostics.formatAll());
    }
    return grammars;
}

void buildMeshLibrary(benchmark::State& state) {
    const std::vector<grammar::CompiledGrammar> grammars = shippedGrammars();
    std::vector<const grammar::CompiledGrammar*> pointers;
    for (const auto& g : grammars) pointers.push_back(&g);
    size_t triangles = 0, meshes = 0;
    for (auto _ : state) {
        const render::TerminalMeshLibrary library(pointers);
        meshes = library.distinctMeshCount();
        triangles = 0;
        for (uint32_t g = 0; g < library.grammarCount(); ++g)
            for (uint16_t s = 0; s < library.shapeCount(g); ++s)
                triangles += library.mesh(g, s).triangleCount();
        benchmark::DoNotOptimize(triangles);
    }
    state.counters["meshes"] = double(meshes);
    state.counters["triangles"] = double(triangles);
}
BENCHMARK(buildMeshLibrary)->Unit(benchmark::kMillisecond);

// The table of docs/BENCHMARKS.md, printed before the timings.
void printMeshTable() {
    const std::vector<grammar::CompiledGrammar> grammars = shippedGrammars();
    std::vector<const grammar::CompiledGrammar*> pointers;
    for (const auto& g : grammars) pointers.push_back(&g);
    const render::TerminalMeshLibrary library(pointers);
    std::printf("| grammar | shape | triangles | declared | vertices | bytes |\n|---|---|---|---|---|---|\n");
    for (uint32_t g = 0; g < library.grammarCount(); ++g) {
        for (uint16_t s = 0; s < library.shapeCount(g); ++s) {
            const render::TerminalMesh& m = library.mesh(g, s);
            std::printf("| %s | %s | %zu | %u | %zu | %zu |\n",
                        std::filesystem::path(grammars[g].name).stem().c_str(), m.shape.c_str(),
                        m.triangleCount(), grammars[g].shapes[s].triangles, m.vertices.size(), m.byteSize());
        }
    }
    std::printf("distinct meshes %zu, %zu bytes\n", library.distinctMeshCount(), library.byteSize());
}

} // namespace

int main(int argc, char** argv) {
    printMeshTable();
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    return 0;
}
