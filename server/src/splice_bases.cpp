#include "hexlod/server/splice_bases.h"

#include <algorithm>
#include <numeric>

namespace hexlod::server {

std::vector<std::pair<uint32_t, uint64_t>>
SpliceBases::hashed(std::span<const grammar::BuildingInput> inputs) {
    std::vector<std::pair<uint32_t, uint64_t>> out;
    out.reserve(inputs.size());
    for (const grammar::BuildingInput& b : inputs) out.emplace_back(b.id, cache::hashBuildingInput(b));
    std::sort(out.begin(), out.end());
    return out;
}

void SpliceBases::remember(uint32_t batch, const cache::BatchKey& key,
                           std::span<const grammar::BuildingInput> inputs) {
    {
        std::lock_guard lock(mutex_);
        const auto found = bases_.find(batch);
        if (found != bases_.end() && found->second.key == key) return;
    }
    Base base{key, hashed(inputs)};
    std::lock_guard lock(mutex_);
    bases_[batch] = std::move(base);
}

std::optional<SpliceBases::Plan> SpliceBases::plan(uint32_t batch, const cache::BatchKey& key,
                                                   std::span<const grammar::BuildingInput> inputs,
                                                   double maxChangedShare) const {
    // Inputs by id, so that they line up with the base's buildings.
    std::vector<uint32_t> byId(inputs.size());
    std::iota(byId.begin(), byId.end(), 0u);
    std::sort(byId.begin(), byId.end(), [&](uint32_t a, uint32_t b) { return inputs[a].id < inputs[b].id; });
    Plan plan;
    {
        std::lock_guard lock(mutex_);
        const auto found = bases_.find(batch);
        if (found == bases_.end()) return std::nullopt;
        const Base& base = found->second;
        if (base.key == key || base.key.grammarHash != key.grammarHash ||
            base.buildings.size() != inputs.size())
            return std::nullopt;
        for (size_t i = 0; i < byId.size(); ++i) {
            const grammar::BuildingInput& input = inputs[byId[i]];
            if (base.buildings[i].first != input.id || (i > 0 && inputs[byId[i - 1]].id == input.id))
                return std::nullopt;
            if (base.buildings[i].second != cache::hashBuildingInput(input)) {
                plan.changed.push_back(byId[i]);
                plan.ids.push_back(input.id);
            }
        }
        plan.base = base.key;
    }
    if (plan.changed.empty() || double(plan.changed.size()) > maxChangedShare * double(inputs.size()))
        return std::nullopt;
    return plan;
}

} // namespace hexlod::server
