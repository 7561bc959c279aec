// Encoded payloads (the exact bytes a content response sends) in a byte-budgeted LRU, keyed
// by batch key, so that a cached request costs a hash lookup and a write, no encoding. The
// decoded sets live in cache::TerminalSetCache below it; this tier only saves the encode.
#pragma once

#include "hexlod/cache/batch_key.h"
#include "hexlod/cache/recency_list.h"

#include <cstdint>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

namespace hexlod::server {

using PayloadBytes = std::shared_ptr<const std::vector<uint8_t>>;

struct PayloadCacheStats {
    uint64_t hits = 0, misses = 0, insertions = 0, evictions = 0;
    uint64_t bytes = 0, entries = 0, budget = 0;
};

// Thread-safe. A payload larger than the whole budget is not kept. Bytes held by a response
// being written stay alive through their shared_ptr after eviction, so the budget bounds what
// the cache holds, not what in-flight responses hold.
class PayloadCache {
public:
    explicit PayloadCache(uint64_t budgetBytes) : budget_(budgetBytes) {}

    PayloadBytes find(const cache::BatchKey& key); // counts a hit or a miss
    PayloadBytes peek(const cache::BatchKey& key); // counts nothing, touches nothing
    void insert(const cache::BatchKey& key, PayloadBytes bytes);
    // As cache::TerminalSetCache's: superseded keys are evicted before current ones.
    void markSuperseded(const cache::BatchKey& key);
    void markCurrent(const cache::BatchKey& key);
    PayloadCacheStats stats() const;

private:
    struct Entry {
        PayloadBytes bytes;
        cache::RecencyList<cache::BatchKey>::Position lru;
    };
    const uint64_t budget_;
    mutable std::mutex mutex_;
    std::unordered_map<cache::BatchKey, Entry, cache::BatchKeyHash> entries_;
    cache::RecencyList<cache::BatchKey> lru_;
    PayloadCacheStats stats_;
};

} // namespace hexlod::server
