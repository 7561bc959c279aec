// The batch catalog: a scene, its cell index, and for every (cell, grammar) batch its cache key
// and the means to generate it (ARCHITECTURE.md §4, "Cache keys"). It is also where parameter
// edits happen at library level: an edit rewrites the selected buildings' parameter values
// and recomputes the keys of exactly the batches holding them, so the next fetch misses the
// cache for those batches only; old entries are never deleted but age out of the LRU, and
// undo() brings the old keys, and so the old entries, back.
//
// Selecting buildings. Inside one grammar a building is its index in that grammar's list
// (scene::GrammarBuildings::buildings), which is the index cells::Batch uses. Across the scene
// a building is its BuildingInput::id: the scene builder numbers the buildings of all building
// grammars from 0 in one sequence, so such an id names one building. Trees are numbered in a
// sequence of their own, so an id never names a tree: select trees by (grammar, index), cell
// or grammar.
//
// Not thread-safe for edits: setParams() and undo() must not run while another thread calls
// generate() or fetch(). A worker that must stay safe snapshots inputsOf() beforehand and
// generates from the snapshot (the scheduler does).
#pragma once

#include "hexlod/cache/batch_key.h"
#include "hexlod/cache/terminal_set_cache.h"
#include "hexlod/cells/cell_index.h"
#include "hexlod/grammar/batch_expander.h"
#include "hexlod/scene/scene_builder.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <variant>
#include <vector>

namespace hexlod::cells {

// A building by grammar (scene order: building grammars, then tree grammars) and its index in
// that grammar's list.
struct BuildingRef {
    uint32_t grammar = 0;
    uint32_t building = 0;
};

// Buildings of the scene's building grammars by BuildingInput::id.
struct BuildingIds {
    std::vector<uint32_t> ids;
};

struct GrammarIndex {
    uint32_t index = 0;
};

// A GrammarBuildings::name: the config's grammar name, or a tree species' grammar path.
struct GrammarName {
    std::string name;
};

using Selector = std::variant<std::vector<BuildingRef>, BuildingIds, HexCoord, GrammarIndex, GrammarName>;

struct KeyChange {
    uint32_t batch = 0; // index into CellIndex::batches()
    cache::BatchKey before, after;
};

struct EditResult {
    bool ok = false;
    std::string error;              // on failure: names the selector part or parameter at fault
    std::vector<KeyChange> changed; // batches whose key changed, ascending by batch
};

class BatchCatalog {
public:
    // Indexes `scene` on cells of scene.config.cellSize. Throws as CellIndex::build does.
    explicit BatchCatalog(scene::BuiltScene scene);

    const scene::BuiltScene& scene() const { return scene_; }
    const CellIndex& index() const { return index_; }
    size_t batchCount() const { return keys_.size(); }
    const Batch& batch(uint32_t batch) const { return index_.batches()[batch]; }
    const cache::BatchKey& key(uint32_t batch) const { return keys_.at(batch); }
    // Index of the cell's first batch; its batches are contiguous (CellIndex sorts them by cell).
    // Throws std::out_of_range for an unoccupied cell.
    uint32_t firstBatchOf(HexCoord cell) const;
    // Building grammars, then tree grammars, as CellIndex numbers them. Throws std::out_of_range.
    const scene::GrammarBuildings& grammar(uint32_t grammar) const;

    // The cell's hexagon centre in world metres at z = 0: what terminal positions are relative to.
    glm::dvec3 cellOrigin(HexCoord cell) const;

    // A copy of the batch's buildings as they are now.
    std::vector<grammar::BuildingInput> inputsOf(uint32_t batch) const;
    // Expands the batch now (header cell, grammar and key filled) without the cache.
    grammar::TerminalSet generate(uint32_t batch) const;
    // The whole expansion of the batch now: its terminal set (as generate() fills it), its
    // extruded set and its issues. For exports and LOD0, which need the base volumes too.
    grammar::BatchResult expand(uint32_t batch) const;
    // The batch's extruded set alone, expanding no further than its stop rules (LOD0, LOD1).
    grammar::ExtrudedSet expandExtruded(uint32_t batch) const;
    // Expands a snapshot taken with inputsOf() under the key the batch had then.
    grammar::TerminalSet generate(uint32_t batch, std::span<const grammar::BuildingInput> inputs,
                                  const cache::BatchKey& key) const;
    // The same expansion with everything it gives: the terminal set (header and key filled),
    // the extruded set and the issues.
    grammar::BatchResult expand(uint32_t batch, std::span<const grammar::BuildingInput> inputs,
                                const cache::BatchKey& key) const;
    // The cached set of the batch's current key, generated on a miss.
    std::shared_ptr<const grammar::TerminalSet> fetch(uint32_t batch, cache::TerminalSetCache& cache) const;

    // Sets `values` on every selected building whose grammar declares the parameter. All or
    // nothing: an empty selection or value list, an unknown grammar, building or cell, a name
    // that no selected grammar declares, or a value that is not finite or lies outside the
    // declared range of any selected grammar fails with an error naming it, and changes nothing.
    // A successful edit goes on the history, even when it changed no key.
    EditResult setParams(const Selector& selector, const scene::ParameterMap& values);
    // Restores the values the last remaining edit replaced; fails when the history is empty.
    EditResult undo();
    size_t historySize() const { return history_.size(); }

private:
    struct SavedParameters {
        BuildingRef building;
        std::vector<float> parameters;
    };
    struct Edit {
        std::vector<SavedParameters> before;
    };

    grammar::BuildingInput& buildingAt(BuildingRef ref);
    bool select(const Selector& selector, std::vector<BuildingRef>& out, std::string& error) const;
    grammar::BatchResult expandSnapshot(uint32_t batch, std::span<const grammar::BuildingInput> inputs,
                                        const cache::BatchKey& key, bool extrudedOnly = false) const;
    cache::BatchKey computeKey(uint32_t batch) const;
    // Recomputes the keys of the batches holding `buildings`; returns those that changed.
    std::vector<KeyChange> rekey(std::span<const SavedParameters> buildings);

    scene::BuiltScene scene_;
    CellIndex index_;
    std::vector<cache::BatchKey> keys_;
    std::vector<std::vector<uint32_t>> batchOfMember_; // per grammar, per building
    std::vector<Edit> history_;
};

} // namespace hexlod::cells
