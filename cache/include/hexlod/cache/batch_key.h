// Cache keys (ARCHITECTURE.md §4 "Cache keys"): a batch's terminal set is a pure function
// of its cell, its grammar's compiled form and its buildings' inputs, so hashing exactly
// those makes an edit change only the keys of the batches it touches, and undoing the edit
// finds the old entry again.
#pragma once

#include "hexlod/grammar/expander.h"
#include "hexlod/grammar/terminal_set.h"

#include <cstdint>
#include <span>
#include <string>

namespace hexlod::cache {

struct BatchKey {
    grammar::CellCoord cell;
    uint32_t grammar = 0;        // index of the grammar in the scene
    uint64_t grammarHash = 0;    // CompiledGrammar::contentHash
    uint64_t parametersHash = 0; // hashBatchParameters of the batch's buildings

    bool operator==(const BatchKey& other) const {
        return cell.q == other.cell.q && cell.r == other.cell.r && grammar == other.grammar &&
               grammarHash == other.grammarHash && parametersHash == other.parametersHash;
    }

    // Stable across runs, builds and machines: it names disk files and HTTP URLs.
    uint64_t digest() const;
    std::string hex() const; // 16 lowercase hex digits of digest(), safe in file names and URLs
};

std::string hexDigest(uint64_t digest); // 16 lowercase hex digits, most significant first

struct BatchKeyHash {
    size_t operator()(const BatchKey& key) const { return static_cast<size_t>(key.digest()); }
};

// Hashes what a batch's terminals depend on besides its cell and grammar: per building its
// id, parameter values, footprint and base elevation, plus the scene seed. Buildings are
// taken in id order, so the input order does not matter. Pass resolved parameter vectors
// (resolveParameters): an empty vector and the explicit defaults expand alike but hash apart.
uint64_t hashBatchParameters(std::span<const grammar::BuildingInput> buildings, uint64_t sceneSeed = 0);
// One building's part of it: its id, parameter values, footprint and base elevation.
uint64_t hashBuildingInput(const grammar::BuildingInput& building);

} // namespace hexlod::cache
