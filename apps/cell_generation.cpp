#include "cell_generation.h"

#include "hexlod/grammar/batch_expander.h"
#include "hexlod/grammar/terminal_set_codec.h"

#include <algorithm>
#include <chrono>

namespace hexlod::apps {
namespace {

const scene::GrammarBuildings& grammarOf(const scene::BuiltScene& scene, const cells::CellIndex& index,
                                         uint32_t grammar) {
    return index.isTreeGrammar(grammar) ? scene.treeGrammars[grammar - index.buildingGrammarCount()]
                                        : scene.buildingGrammars[grammar];
}

nlohmann::json spread(std::vector<double> values) {
    if (values.empty()) return {{"median", 0}, {"p95", 0}, {"max", 0}};
    std::sort(values.begin(), values.end());
    auto at = [&](double q) { return values[static_cast<size_t>(q * double(values.size() - 1) + 0.5)]; };
    return {{"median", at(0.5)}, {"p95", at(0.95)}, {"max", values.back()}};
}

} // namespace

nlohmann::json generateCells(const scene::BuiltScene& scene, const cells::CellIndex& index,
                             uint32_t maxCells) {
    using Clock = std::chrono::steady_clock;
    const size_t total = index.cells().size();
    const size_t count = maxCells == 0 ? total : std::min<size_t>(total, maxCells);
    std::vector<double> milliseconds, bytes, encodedBytes, terminals, buildingBytes, buildingEncoded;
    std::vector<grammar::BuildingInput> members;
    for (size_t k = 0; k < count; ++k) {
        // Evenly spaced over the sorted cells, so a sample spans the centre and the edge.
        const cells::CellBounds& cell = index.cells()[k * total / count];
        const glm::dvec2 centre = index.grid().center(cell.cell);
        double cellMilliseconds = 0.0;
        uint64_t cellBytes = 0, cellEncoded = 0, cellTerminals = 0, cellBuildingBytes = 0,
                 cellBuildingEncoded = 0;
        for (const cells::Batch& batch : index.batchesOf(cell.cell)) {
            const scene::GrammarBuildings& source = grammarOf(scene, index, batch.grammar);
            members.clear();
            for (uint32_t b : batch.buildings) members.push_back(source.buildings[b]);
            grammar::BatchInput input;
            input.grammar = &source.grammar;
            input.buildings = members;
            input.settings.seed = scene.config.seed;
            input.settings.cellOrigin = glm::dvec3(centre, 0.0);
            input.cell = {cell.cell.q, cell.cell.r};
            input.grammarIndex = batch.grammar;
            const Clock::time_point start = Clock::now();
            const grammar::BatchResult result = grammar::expandBatch(input);
            cellMilliseconds += std::chrono::duration<double, std::milli>(Clock::now() - start).count();
            const size_t encoded = grammar::encodeTerminalSet(result.terminals).size();
            cellBytes += result.terminals.byteSize();
            cellEncoded += encoded;
            if (!index.isTreeGrammar(batch.grammar)) {
                cellBuildingBytes += result.terminals.byteSize();
                cellBuildingEncoded += encoded;
            }
            cellTerminals += result.terminals.records.size();
        }
        milliseconds.push_back(cellMilliseconds);
        bytes.push_back(double(cellBytes));
        encodedBytes.push_back(double(cellEncoded));
        terminals.push_back(double(cellTerminals));
        buildingBytes.push_back(double(cellBuildingBytes));
        buildingEncoded.push_back(double(cellBuildingEncoded));
    }
    return {
        {"cells_generated", count},
        {"milliseconds_per_cell", spread(milliseconds)},
        {"bytes_per_cell", spread(bytes)},
        {"encoded_bytes_per_cell", spread(encodedBytes)},
        {"terminals_per_cell", spread(terminals)},
        // Tree batches only matter near the camera (far trees are billboards), so the
        // buildings' share is reported on its own.
        {"building_bytes_per_cell", spread(buildingBytes)},
        {"building_encoded_bytes_per_cell", spread(buildingEncoded)},
    };
}

} // namespace hexlod::apps
