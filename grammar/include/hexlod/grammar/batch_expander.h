// Batch expansion: many buildings of one grammar in one call, in parallel with oneTBB.
// The output is byte-identical whatever the thread count or the order of the input.
#pragma once

#include "hexlod/grammar/expander.h"

#include <span>

namespace hexlod::grammar {

struct BatchInput {
    const CompiledGrammar* grammar = nullptr;
    std::span<const BuildingInput> buildings;
    ExpansionSettings settings;
    CellCoord cell;
    uint32_t grammarIndex = 0;
};

// Issues folded per (kind, rule) so a million NaN tiles make one line, not a million.
struct BatchIssue {
    ExpansionIssue first; // the first occurrence in building-id order
    uint64_t occurrences = 0;
};

struct BatchResult {
    TerminalSet terminals;
    ExtrudedSet extruded;
    std::vector<BatchIssue> issues;
    uint64_t atoms = 0;
    uint32_t buildingsExpanded = 0;
    uint32_t buildingsSkipped = 0;
    bool failed = false; // a batch-level cap was hit; `terminals` is empty
};

// Runs on the calling thread's TBB arena; limit threads with tbb::global_control.
BatchResult expandBatch(const BatchInput& input);

} // namespace hexlod::grammar
