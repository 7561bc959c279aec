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
    lru_.splice(lru_.begin(), lru_, it->second.lru);
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
    lru_.push_front(key);
    stats_.bytes += bytes->size();
    it->second = {std::move(bytes), lru_.begin()};
    ++stats_.insertions;
    while (stats_.bytes > budget_) {
        const auto oldest = entries_.find(lru_.back());
        stats_.bytes -= oldest->second.bytes->size();
        entries_.erase(oldest);
        lru_.pop_back();
        ++stats_.evictions;
    }
}

PayloadCacheStats PayloadCache::stats() const {
    std::lock_guard lock(mutex_);
    PayloadCacheStats s = stats_;
    s.entries = entries_.size();
    s.budget = budget_;
    return s;
}

} // namespace hexlod::server
