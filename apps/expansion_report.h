// Timing and statistics of one expanded batch, shared by every form of `hexlod expand`.
#pragma once

#include "hexlod/grammar/batch_expander.h"

#include <nlohmann/json.hpp>

#include <string>

namespace hexlod::apps {

struct Timing {
    double medianSeconds = 0.0;
    double coldSeconds = 0.0; // the first run, before any memory is recycled
    grammar::BatchResult result;
};

// Expands `repeat` times (at least once); keeps the first result and the median time.
Timing timeExpansion(const grammar::BatchInput& input, uint32_t repeat);

// The statistics object documented in README.md ("Command line").
nlohmann::json batchStats(const grammar::CompiledGrammar& g, const std::string& name, size_t buildings,
                          uint32_t threads, uint32_t repeat, const Timing& timing);
void printBatchStats(const nlohmann::json& stats);

// Prints the batch's issues to stderr; returns true if any is an error.
bool reportIssues(const grammar::CompiledGrammar& g, const grammar::BatchResult& result);

} // namespace hexlod::apps
