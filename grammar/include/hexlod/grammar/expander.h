// Segment-based expansion of one building (thesis §4.4.2): every footprint edge is a 1D
// atom that the compiled rule map grows into terminals. Caps on depth, work and output
// turn runaway grammars into diagnostics instead of hangs.
#pragma once

#include "hexlod/grammar/bulk_allocator.h"
#include "hexlod/grammar/compiled_grammar.h"
#include "hexlod/grammar/extruded_set.h"
#include "hexlod/grammar/terminal_set.h"

#include <glm/glm.hpp>

#include <span>

#include <string>
#include <vector>

namespace hexlod::grammar {

struct ExpansionLimits {
    uint32_t maxDepth = 256;                    // rule applications on one derivation path
    uint32_t maxTerminalsPerAtom = 1u << 20;    // ~1M: a 1000-floor tower face fits easily
    uint32_t maxOperationsPerAtom = 1u << 23;   // rule applications per atom, bounds Branch blow-ups
    uint32_t maxPendingScopes = 1u << 20;       // scopes waiting on the stack: bounds memory (~100 MiB)
    uint64_t maxTerminalsPerBatch = 1ull << 25; // 32M records = 1 GiB
};

struct ExpansionSettings {
    uint64_t seed = 0;          // scene seed
    glm::dvec3 cellOrigin{0.0}; // terminal positions are relative to it
    ExpansionLimits limits;
    // Stop at the extruded set: scopes entering a stop rule are recorded and go no further, so
    // LOD0 and LOD1 cells get their base volumes for the cost of the first rules only.
    bool extrudedOnly = false;
};

struct BuildingInput {
    uint32_t id = 0;
    std::vector<glm::dvec2> footprint; // world metres: x east, y north
    double baseElevation = 0.0;        // world z of the ground
    std::vector<float> parameters;     // resolveParameters() output; empty means the defaults
};

enum class IssueKind : uint8_t {
    DepthCap,
    AtomTerminalCap,
    AtomOperationCap,
    BatchTerminalCap,
    InvalidSize,
    TooManyTiles,
    InvalidCount,
    InvalidProbability,
    InvalidTransform,
    WrongScopeKind,
    DegenerateFootprint,
    SelfIntersectingFootprint,
    DuplicateBuilding,
    BadParameters,
};
const char* issueKindName(IssueKind kind);
bool issueIsError(IssueKind kind); // errors drop output; the rest are warnings

struct ExpansionIssue {
    IssueKind kind = IssueKind::InvalidSize;
    uint32_t rule = kNullRule; // the rule that hit it, if any
    uint32_t building = 0;
    std::string detail;
};

using TerminalBuffer = std::vector<TerminalRecord, BulkAllocator<TerminalRecord>>;

// Where a batch worker keeps the terminals of its buildings: fixed blocks that are never
// reallocated, so a building's span stays valid and no record is copied twice. Growing one
// buffer instead re-copied hundreds of megabytes and faulted in fresh pages at each step.
class TerminalArena {
public:
    static constexpr size_t kBlockRecords = size_t(1) << 17; // 4 MiB, the bulk threshold
    std::span<const TerminalRecord> append(std::span<const TerminalRecord> records);

private:
    std::vector<TerminalBuffer> blocks_;
};

struct BuildingOutput {
    std::vector<TerminalRecord> terminals;          // in derivation order, from expand(building, out)
    std::span<const TerminalRecord> arenaTerminals; // from expand(building, out, arena)
    std::vector<glm::vec2> footprint;               // cleaned, cell-local
    std::vector<ExtrudedElement> elements;
    std::vector<ExpansionIssue> issues;
    float baseElevation = 0.0f;
    float height = 0.0f;
    uint32_t atoms = 0;
    bool skipped = false; // the footprint was unusable
};

// Expands buildings one at a time, reusing its scratch memory; one per thread.
class BuildingExpander {
public:
    BuildingExpander(const CompiledGrammar& grammar, const ExpansionSettings& settings);
    ~BuildingExpander();
    BuildingExpander(const BuildingExpander&) = delete;
    BuildingExpander& operator=(const BuildingExpander&) = delete;

    void expand(const BuildingInput& building, BuildingOutput& out);
    // Appends the terminals to `arena` instead of a vector of their own: the batch path,
    // which saves an allocation per building.
    void expand(const BuildingInput& building, BuildingOutput& out, TerminalArena& arena);

private:
    struct Impl;
    Impl* impl_;
};

// Formats an issue for people: "file:line:col: rule 'Name': building 12: <what happened>".
std::string describeIssue(const CompiledGrammar& grammar, const ExpansionIssue& issue,
                          uint64_t occurrences = 1);

} // namespace hexlod::grammar
