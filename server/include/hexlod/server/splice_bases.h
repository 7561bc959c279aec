// What an edited batch can be spliced from (grammar/batch_splice.h): per batch, the key of
// the last terminal set the service made for it and a hash of each of its buildings' inputs
// then. A new key's inputs, compared with them, name the buildings that differ, whatever
// sequence of edits and undos led there.
#pragma once

#include "hexlod/cache/batch_key.h"
#include "hexlod/grammar/expander.h"

#include <cstdint>
#include <mutex>
#include <optional>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

namespace hexlod::server {

class SpliceBases {
public:
    struct Plan {
        cache::BatchKey base;          // the set to splice into
        std::vector<uint32_t> changed; // indices into the inputs of the buildings that differ
        std::vector<uint32_t> ids;     // their building ids, ascending
    };

    // Remembers `key`, made from `inputs`, as the batch's base.
    void remember(uint32_t batch, const cache::BatchKey& key, std::span<const grammar::BuildingInput> inputs);
    // How to make `key` from `inputs` by splicing into the batch's base. None when the batch
    // has no base, the base is `key` or of another grammar, the building ids differ from the
    // base's or repeat, or more than `maxChangedShare` of the buildings differ (splicing
    // then saves too little).
    std::optional<Plan> plan(uint32_t batch, const cache::BatchKey& key,
                             std::span<const grammar::BuildingInput> inputs, double maxChangedShare) const;

private:
    struct Base {
        cache::BatchKey key;
        std::vector<std::pair<uint32_t, uint64_t>> buildings; // (id, input hash), ascending
    };
    static std::vector<std::pair<uint32_t, uint64_t>> hashed(std::span<const grammar::BuildingInput> inputs);

    mutable std::mutex mutex_;
    std::unordered_map<uint32_t, Base> bases_;
};

} // namespace hexlod::server
