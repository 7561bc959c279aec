// SceneService: the tree species it serves, and baking new ones for edited trees.
#include "hexlod/server/scene_service.h"

#include "hexlod/grammar/terminal_set_codec.h"

#include <map>

namespace hexlod::server {

std::optional<SpeciesAsset> SceneService::species(uint32_t index) const {
    std::lock_guard lock(speciesMutex_);
    if (index >= species_.size()) return std::nullopt;
    return species_[index]; // a copy: the list may grow meanwhile, the bytes are shared
}

size_t SceneService::speciesCount() const {
    std::lock_guard lock(speciesMutex_);
    return species_.size();
}

void SceneService::attachSpeciesBakery(std::unique_ptr<SpeciesBakery> bakery) {
    bakery_ = std::move(bakery);
}

void SceneService::requestMissingSpecies(const std::vector<cells::KeyChange>& changes) {
    if (!bakery_ || !assets_.speciesServed) return; // a client draws no billboards then
    std::vector<SpeciesRequest> requests;
    {
        std::lock_guard lock(speciesMutex_);
        bool retiredOnce = false;
        size_t held = editedHeld();
        for (const cells::KeyChange& change : changes) {
            const cells::Batch& batch = catalog_->batch(change.batch);
            if (!catalog_->index().isTreeGrammar(batch.grammar)) continue;
            const scene::GrammarBuildings& trees = catalog_->grammar(batch.grammar);
            for (const uint32_t member : batch.buildings) {
                const std::vector<float>& values = trees.buildings[member].parameters;
                if (speciesStates_.count({batch.grammar, values})) continue;
                // Past the cap, trees of new values stay terminals: an endless run of edits
                // must not grow the served atlases without bound. Species no tree has any
                // more make room first (once: the scan reads every tree).
                if (held >= kMaxEditedSpecies && !retiredOnce) {
                    retiredOnce = true;
                    retireUnusedSpecies();
                    held = editedHeld();
                }
                if (held >= kMaxEditedSpecies) break;
                speciesStates_[{batch.grammar, values}] = SpeciesState::Baking;
                ++held;
                // Named by its values, so that the same values baked after a restart find
                // their atlas in the impostor store under the same name.
                const uint64_t digest = grammar::checksum64(std::span(
                    reinterpret_cast<const uint8_t*>(values.data()), values.size() * sizeof(float)));
                requests.push_back(
                    {batch.grammar, values, trees.name + " edited " + cache::hexDigest(digest), {}});
            }
        }
    }
    for (SpeciesRequest& request : requests) {
        const SpeciesRequest key{request.grammar, request.parameters, {}, {}};
        request.stillWanted = [this, key] { return speciesStillWanted({key.grammar, key.parameters}); };
        bakery_->bake(std::move(request),
                      [this, key](std::optional<SpeciesAsset> asset, const std::string& error) {
                          addBakedSpecies(key, std::move(asset), error);
                      });
    }
}

size_t SceneService::editedHeld() const {
    size_t held = 0;
    for (const auto& [values, state] : speciesStates_) held += state == SpeciesState::Baking;
    for (size_t s = startSpecies_; s < species_.size(); ++s) held += !species_[s].retired;
    return held;
}

bool SceneService::treesHaveValues(uint32_t grammar, const std::vector<float>& values) const {
    for (const grammar::BuildingInput& tree : catalog_->grammar(grammar).buildings)
        if (tree.parameters == values) return true;
    return false;
}

bool SceneService::speciesStillWanted(const std::pair<uint32_t, std::vector<float>>& values) {
    std::shared_lock catalogLock(catalogMutex_);
    if (treesHaveValues(values.first, values.second)) return true;
    std::lock_guard lock(speciesMutex_);
    // Forgotten rather than failed: an undo back to these values asks for them again.
    speciesStates_.erase(values);
    ++speciesDropped_;
    return false;
}

void SceneService::retireUnusedSpecies() {
    // The served edited species (at most the cap) by grammar and values, crossed off as trees
    // have them: one pass over each grammar's trees, no copy of their values.
    std::map<uint32_t, std::map<std::vector<float>, size_t>> unused;
    for (size_t s = startSpecies_; s < species_.size(); ++s)
        if (!species_[s].retired) unused[species_[s].grammar].emplace(species_[s].parameters, s);
    for (auto& [g, ofGrammar] : unused)
        for (const grammar::BuildingInput& tree : catalog_->grammar(g).buildings)
            ofGrammar.erase(tree.parameters);
    for (const auto& [g, ofGrammar] : unused) {
        for (const auto& [values, s] : ofGrammar) {
            speciesStates_.erase({g, values});
            species_[s].retired = true;
            species_[s].impostor = {}; // its files' bytes: what the cap bounds
        }
    }
}

void SceneService::addBakedSpecies(const SpeciesRequest& request, std::optional<SpeciesAsset> asset,
                                   const std::string& error) {
    nlohmann::json event;
    {
        std::lock_guard lock(speciesMutex_);
        SpeciesState& state = speciesStates_[{request.grammar, request.parameters}];
        if (!asset) {
            state = SpeciesState::Failed; // not asked for again: the same values fail the same way
            event = {{"error", error}, {"grammar", request.grammar}, {"tree_species", species_.size()}};
        } else {
            state = SpeciesState::Served;
            asset->impostor.layer = uint32_t(species_.size());
            species_.push_back(std::move(*asset));
            event = {{"species", speciesEntryJson(uint32_t(species_.size() - 1))},
                     {"tree_species", species_.size()}};
        }
    }
    events_.notify(event.contains("species") ? "species" : "species-failed", event.dump());
}

void SceneService::renderSpeciesMetrics(PrometheusText& out) const {
    std::map<SpeciesState, size_t> counts;
    uint64_t dropped = 0, retired = 0;
    {
        std::lock_guard lock(speciesMutex_);
        for (const auto& [values, state] : speciesStates_) ++counts[state];
        dropped = speciesDropped_;
        for (const SpeciesAsset& species : species_) retired += species.retired;
    }
    out.family("hexlod_tree_species", "gauge",
               "Tree species by state: served, being baked for an edit, or failed to bake.");
    for (const auto& [state, name] : {std::pair{SpeciesState::Served, "served"},
                                      {SpeciesState::Baking, "baking"},
                                      {SpeciesState::Failed, "failed"}})
        out.sample("hexlod_tree_species", {{"state", name}}, static_cast<double>(counts[state]));
    out.family("hexlod_tree_species_dropped_total", "counter",
               "Species bakes dropped before they began: no tree had their values any more.");
    out.sample("hexlod_tree_species_dropped_total", {}, static_cast<double>(dropped));
    out.family("hexlod_tree_species_retired_total", "counter",
               "Species baked for edits and retired at the cap: no tree had their values any more.");
    out.sample("hexlod_tree_species_retired_total", {}, static_cast<double>(retired));
}

} // namespace hexlod::server
