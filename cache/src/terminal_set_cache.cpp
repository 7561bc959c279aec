#include "hexlod/cache/terminal_set_cache.h"

#include "disk_tier.h"
#include "disk_writer.h"

#include <algorithm>
#include <chrono>

namespace hexlod::cache {

TerminalSetCache::TerminalSetCache(CacheOptions options) : options_(std::move(options)) {
    if (!options_.diskPath.empty()) {
        disk_ = std::make_unique<DiskTier>(options_.diskPath, options_.diskBudgetBytes, options_.zstdLevel);
        // Sets waiting for the writer are pinned in memory: a quarter of the budget keeps the
        // memory tier near its bound while letting a burst of generations run ahead.
        writer_ = std::make_unique<DiskWriter>(*disk_, options_.memoryBudgetBytes / 4);
    }
}

TerminalSetCache::~TerminalSetCache() = default;

TerminalSetCache::SetPtr TerminalSetCache::findInMemoryLocked(const BatchKey& key) {
    const auto it = entries_.find(key);
    if (it == entries_.end()) return nullptr;
    lru_.touch(it->second.lru);
    ++stats_.lookups;
    ++stats_.hits;
    ++stats_.memoryHits;
    SetPtr hit = it->second.set;
    trimLocked(nullptr); // `hit` pins the entry, so the trim cannot take it
    return hit;
}

TerminalSetCache::SetPtr TerminalSetCache::promoteFromDisk(const BatchKey& key) {
    std::optional<grammar::TerminalSet> loaded = disk_->load(key); // file I/O without our lock
    if (!loaded) return nullptr;
    SetPtr set = std::make_shared<const grammar::TerminalSet>(std::move(*loaded));
    std::lock_guard lock(mutex_);
    ++stats_.lookups;
    ++stats_.hits;
    ++stats_.diskHits;
    insertLocked(key, set, nullptr);
    return set;
}

TerminalSetCache::SetPtr TerminalSetCache::find(const BatchKey& key) {
    {
        std::lock_guard lock(mutex_);
        if (SetPtr hit = findInMemoryLocked(key)) return hit;
    }
    if (disk_)
        if (SetPtr promoted = promoteFromDisk(key)) return promoted;
    std::lock_guard lock(mutex_);
    ++stats_.lookups;
    ++stats_.misses;
    trimLocked(nullptr);
    return nullptr;
}

TerminalSetCache::SetPtr TerminalSetCache::findInMemory(const BatchKey& key) {
    std::lock_guard lock(mutex_);
    return findInMemoryLocked(key);
}

void TerminalSetCache::insert(const BatchKey& key, grammar::TerminalSet set) {
    const SetPtr shared = std::make_shared<const grammar::TerminalSet>(std::move(set));
    {
        std::lock_guard lock(mutex_);
        insertLocked(key, shared, shared.get());
    }
    if (writer_) writer_->enqueue(key, shared);
}

TerminalSetCache::SetPtr
TerminalSetCache::getOrGenerate(const BatchKey& key, const std::function<grammar::TerminalSet()>& generate) {
    std::promise<SetPtr> promise;
    {
        std::unique_lock lock(mutex_);
        if (SetPtr hit = findInMemoryLocked(key)) return hit;
        const auto running = generating_.find(key);
        if (running != generating_.end()) {
            const std::shared_future<SetPtr> result = running->second;
            ++stats_.lookups;
            ++stats_.hits;
            ++stats_.sharedGenerations;
            lock.unlock();
            return result.get();
        }
        generating_.emplace(key, promise.get_future().share());
    }
    SetPtr result;
    bool generated = false;
    try {
        if (disk_) result = promoteFromDisk(key);
        if (!result) {
            {
                std::lock_guard lock(mutex_);
                ++stats_.lookups;
                ++stats_.misses;
            }
            const auto start = std::chrono::steady_clock::now();
            result = std::make_shared<const grammar::TerminalSet>(generate());
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            generated = true;
            std::lock_guard lock(mutex_);
            ++stats_.generations;
            stats_.generationSecondsTotal += seconds;
            stats_.generationSecondsMax = std::max(stats_.generationSecondsMax, seconds);
            insertLocked(key, result, nullptr);
        }
    } catch (...) {
        {
            std::lock_guard lock(mutex_);
            generating_.erase(key);
        }
        promise.set_exception(std::current_exception());
        throw;
    }
    {
        std::lock_guard lock(mutex_);
        generating_.erase(key);
    }
    promise.set_value(result);
    // Waiters already have the set; the writer's thread pays for compression and the write.
    if (generated && writer_) writer_->enqueue(key, result);
    return result;
}

void TerminalSetCache::markSuperseded(const BatchKey& key) {
    std::lock_guard lock(mutex_);
    if (const auto it = entries_.find(key); it != entries_.end()) lru_.supersede(it->second.lru);
}

void TerminalSetCache::markCurrent(const BatchKey& key) {
    std::lock_guard lock(mutex_);
    if (const auto it = entries_.find(key); it != entries_.end()) lru_.touch(it->second.lru);
}

void TerminalSetCache::trim() {
    std::lock_guard lock(mutex_);
    trimLocked(nullptr);
}

void TerminalSetCache::flushDisk() {
    if (writer_) writer_->flush();
    trim(); // what the writes unpinned
}

void TerminalSetCache::insertLocked(const BatchKey& key, const SetPtr& set,
                                    const grammar::TerminalSet* ours) {
    auto [it, added] = entries_.try_emplace(key);
    Entry& entry = it->second;
    if (!added) {
        stats_.memoryBytes -= entry.bytes;
        lru_.erase(entry.lru);
    }
    entry = {set, set->heldBytes(), lru_.pushFront(key)};
    stats_.memoryBytes += entry.bytes;
    ++stats_.insertions;
    trimLocked(ours);
}

void TerminalSetCache::trimLocked(const grammar::TerminalSet* ours) {
    // use_count is exact here: new holders only come from copies made under this mutex,
    // and a holder letting go concurrently can only make an entry look pinned a little longer.
    for (auto it = lru_.end(); it != lru_.begin() && stats_.memoryBytes > options_.memoryBudgetBytes;) {
        --it;
        const auto entry = entries_.find(it->key);
        const long holders = entry->second.set.use_count() - (entry->second.set.get() == ours ? 1 : 0);
        if (holders > 1) continue;
        stats_.memoryBytes -= entry->second.bytes;
        ++stats_.evictions;
        entries_.erase(entry);
        it = lru_.erase(it);
    }
}

CacheStats TerminalSetCache::stats() const {
    CacheStats s;
    {
        std::lock_guard lock(mutex_);
        s = stats_;
        s.memoryEntries = entries_.size();
        for (const auto& [key, entry] : entries_)
            if (entry.set.use_count() > 1) s.pinnedBytes += entry.bytes;
    }
    if (disk_) {
        const DiskTierStats disk = disk_->stats();
        s.diskEvictions = disk.evictions;
        s.diskBytes = disk.bytes;
        s.diskFiles = disk.files;
        s.corruptFilesDropped = disk.corruptFilesDropped;
        s.diskWriteFailures = disk.writeFailures;
        s.diskLoadSecondsTotal = disk.loadSeconds;
        s.diskStoreSecondsTotal = disk.storeSeconds;
    }
    return s;
}

} // namespace hexlod::cache
