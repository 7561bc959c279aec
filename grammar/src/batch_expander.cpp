#include "hexlod/grammar/batch_expander.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <map>
#include <numeric>

namespace hexlod::grammar {
namespace {

// Building-id order makes the output independent of input order; ties keep input order
// only for duplicates, which are skipped and reported.
std::vector<uint32_t> orderById(std::span<const BuildingInput> buildings) {
    std::vector<uint32_t> order(buildings.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return buildings[a].id < buildings[b].id; });
    return order;
}

void foldIssues(const std::vector<BuildingOutput>& outputs, BatchResult& result) {
    std::map<std::pair<IssueKind, uint32_t>, BatchIssue> folded;
    for (const BuildingOutput& out : outputs) {
        for (const ExpansionIssue& issue : out.issues) {
            BatchIssue& entry = folded[{issue.kind, issue.rule}];
            if (entry.occurrences++ == 0) entry.first = issue;
        }
    }
    for (auto& [key, issue] : folded) result.issues.push_back(std::move(issue));
}

int wallMaterialParameter(const CompiledGrammar& grammar) {
    return grammar.findParameter("wall_material");
}

void gatherExtruded(const CompiledGrammar& grammar, const std::vector<BuildingOutput>& outputs,
                    std::span<const BuildingInput> buildings, const std::vector<uint32_t>& order,
                    ExtrudedSet& set) {
    const int material = wallMaterialParameter(grammar);
    const std::vector<float> defaults = grammar.defaultParameters();
    for (size_t i = 0; i < outputs.size(); ++i) {
        const BuildingOutput& out = outputs[i];
        if (out.skipped) continue;
        const BuildingInput& in = buildings[order[i]];
        const std::vector<float>& params =
            in.parameters.size() == grammar.params.size() ? in.parameters : defaults;
        ExtrudedBuilding b;
        b.building = in.id;
        b.firstVertex = static_cast<uint32_t>(set.footprints.size());
        b.vertexCount = static_cast<uint32_t>(out.footprint.size());
        b.firstElement = static_cast<uint32_t>(set.elements.size());
        b.elementCount = static_cast<uint32_t>(out.elements.size());
        b.firstParameter = static_cast<uint32_t>(set.parameters.size());
        b.baseElevation = out.baseElevation;
        b.height = out.height;
        b.wallMaterial =
            material >= 0 ? static_cast<uint16_t>(std::clamp(params[material], 0.0f, 65535.0f)) : 0;
        set.buildings.push_back(b);
        set.footprints.insert(set.footprints.end(), out.footprint.begin(), out.footprint.end());
        set.elements.insert(set.elements.end(), out.elements.begin(), out.elements.end());
        set.parameters.insert(set.parameters.end(), params.begin(), params.end());
    }
}

// Counting sort by shape, stable in building order, so each shape is one contiguous range.
// Buildings are cut into chunks that count and scatter in parallel; chunk-major offsets keep
// the result identical to a sequential pass whatever the thread count.
void gatherTerminals(const CompiledGrammar& grammar, const std::vector<BuildingOutput>& outputs,
                     TerminalSet& set) {
    const size_t shapes = grammar.shapes.size();
    const size_t chunks = std::min<size_t>(outputs.size(), 256);
    auto chunkBegin = [&](size_t c) { return outputs.size() * c / std::max<size_t>(chunks, 1); };
    std::vector<size_t> offsets(chunks * shapes, 0); // counts first, then start offsets
    tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
        size_t* counts = &offsets[c * shapes];
        for (size_t i = chunkBegin(c); i < chunkBegin(c + 1); ++i) {
            for (const TerminalRecord& t : outputs[i].arenaTerminals) ++counts[t.shapeAndDepth & 0xffffu];
        }
    });
    set.countPerShape.assign(shapes, 0);
    size_t total = 0;
    for (size_t s = 0; s < shapes; ++s) {
        for (size_t c = 0; c < chunks; ++c) {
            const size_t count = offsets[c * shapes + s];
            offsets[c * shapes + s] = total;
            total += count;
            set.countPerShape[s] += static_cast<uint32_t>(count);
        }
    }
    set.records.resize(total);
    tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
        size_t* cursor = &offsets[c * shapes];
        for (size_t i = chunkBegin(c); i < chunkBegin(c + 1); ++i) {
            for (const TerminalRecord& t : outputs[i].arenaTerminals)
                set.records[cursor[t.shapeAndDepth & 0xffffu]++] = t;
        }
    });
}

} // namespace

BatchResult expandBatch(const BatchInput& input) {
    const CompiledGrammar& grammar = *input.grammar;
    BatchResult result;
    result.terminals.header.cell = input.cell;
    result.terminals.header.grammar = input.grammarIndex;
    result.terminals.header.grammarHash = grammar.contentHash;
    for (int i = 0; i < 3; ++i) result.terminals.header.cellOrigin[i] = input.settings.cellOrigin[i];

    const std::vector<uint32_t> order = orderById(input.buildings);
    std::vector<BuildingOutput> outputs(order.size());
    // Each worker appends its buildings' terminals to its own arena; buildings remember
    // their span, so the gather below still reads them in building-id order.
    struct Worker {
        Worker(const CompiledGrammar& g, const ExpansionSettings& s) : expander(g, s) {}
        BuildingExpander expander;
        TerminalArena arena;
    };
    tbb::enumerable_thread_specific<Worker> workers(std::cref(grammar), std::cref(input.settings));
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, order.size(), 16), [&](const tbb::blocked_range<size_t>& range) {
            Worker& worker = workers.local();
            for (size_t i = range.begin(); i != range.end(); ++i) {
                if (i > 0 && input.buildings[order[i]].id == input.buildings[order[i - 1]].id) {
                    outputs[i].skipped = true;
                    outputs[i].issues.push_back(
                        {IssueKind::DuplicateBuilding, kNullRule, input.buildings[order[i]].id, {}});
                    continue;
                }
                worker.expander.expand(input.buildings[order[i]], outputs[i], worker.arena);
            }
        });

    foldIssues(outputs, result);
    uint64_t terminals = 0;
    for (const BuildingOutput& out : outputs) {
        terminals += out.arenaTerminals.size();
        result.atoms += out.atoms;
        ++(out.skipped ? result.buildingsSkipped : result.buildingsExpanded);
    }
    if (terminals > input.settings.limits.maxTerminalsPerBatch) {
        // Whole or nothing: a batch cut at an arbitrary building would be a silent wrong result.
        result.failed = true;
        result.issues.push_back({{IssueKind::BatchTerminalCap, kNullRule, 0,
                                  std::to_string(terminals) + " terminals, cap " +
                                      std::to_string(input.settings.limits.maxTerminalsPerBatch)},
                                 1});
        return result;
    }
    gatherTerminals(grammar, outputs, result.terminals);
    gatherExtruded(grammar, outputs, input.buildings, order, result.extruded);
    return result;
}

} // namespace hexlod::grammar
