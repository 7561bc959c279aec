#include "hexlod/server/payload_cache.h"

namespace hexlod::server {

PayloadBytes PayloadCache::find(const cache::BatchKey& key) {
    std::lock_guard lock(mutex_);
    const auto it = entries_.find(key);
    if (it == entries_.end()) {
        ++stats_.misses;
        return nullptr;
    }
    ++stats_.hits;
    lru_.touch(it->second.lru);
    return it->second.bytes;
}

PayloadBytes PayloadCache::peek(const cache::BatchKey& key) {
    std::lock_guard lock(mutex_);
    const auto it = entries_.find(key);
    return it == entries_.end() ? nullptr : it->second.bytes;
}

void PayloadCache::insert(const cache::BatchKey& key, PayloadBytes bytes) {
    if (!bytes || bytes->size() > budget_) return;
    std::lock_guard lock(mutex_);
    const auto [it, added] = entries_.try_emplace(key);
    if (!added) {
        stats_.bytes -= it->second.bytes->size();
        lru_.erase(it->second.lru);
    }
    stats_.bytes += bytes->size();
    it->second = {std::move(bytes), lru_.pushFront(key)};
    ++stats_.insertions;
    while (stats_.bytes > budget_) {
        const auto coldest = lru_.coldest();
        const auto oldest = entries_.find(coldest->key);
        stats_.bytes -= oldest->second.bytes->size();
        entries_.erase(oldest);
        lru_.erase(coldest);
        ++stats_.evictions;
    }
}

void PayloadCache::markSuperseded(const cache::BatchKey& key) {
    std::lock_guard lock(mutex_);
    if (const auto it = entries_.find(key); it != entries_.end()) lru_.supersede(it->second.lru);
}

void PayloadCache::markCurrent(const cache::BatchKey& key) {
    std::lock_guard lock(mutex_);
    if (const auto it = entries_.find(key); it != entries_.end()) lru_.touch(it->second.lru);
}

PayloadCacheStats PayloadCache::stats() const {
    std::lock_guard lock(mutex_);
    PayloadCacheStats s = stats_;
    s.entries = entries_.size();
    s.budget = budget_;
    return s;
}

} // namespace hexlod::server
