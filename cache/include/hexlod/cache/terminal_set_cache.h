// The terminal-set cache (thesis §7.5.1–7.5.2): batches expand on demand and stay in
// memory within a byte budget, least recently used first out, with an optional zstd disk
// tier below so that a restart or an evicted cell does not pay for expansion again.
#pragma once

#include "hexlod/cache/batch_key.h"
#include "hexlod/cache/recency_list.h"
#include "hexlod/grammar/terminal_set.h"

#include <cstdint>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>

namespace hexlod::cache {

class DiskTier;
class DiskWriter;

struct CacheOptions {
    uint64_t memoryBudgetBytes = uint64_t(512) << 20;
    uint64_t diskBudgetBytes = uint64_t(4) << 30;
    std::string diskPath; // empty: no disk tier
    int zstdLevel = 3;    // for disk files
};

// Every lookup (find or getOrGenerate) is exactly one of: a memory hit, a disk hit, a wait
// for another thread's generation of the same key, or a miss. So
// lookups == hits + misses and hits == memoryHits + diskHits + sharedGenerations.
struct CacheStats {
    uint64_t lookups = 0;
    uint64_t hits = 0;
    uint64_t misses = 0;
    uint64_t memoryHits = 0;
    uint64_t diskHits = 0;
    uint64_t sharedGenerations = 0;
    uint64_t insertions = 0; // into the memory tier: inserts, generations and disk promotions
    uint64_t evictions = 0;  // memory entries dropped for the budget
    uint64_t memoryBytes = 0;
    uint64_t memoryEntries = 0;
    uint64_t pinnedBytes = 0; // held outside the cache, so not evictable now
    uint64_t diskEvictions = 0;
    uint64_t diskBytes = 0;
    uint64_t diskFiles = 0;
    uint64_t corruptFilesDropped = 0;
    uint64_t diskWriteFailures = 0;
    uint64_t generations = 0;
    double generationSecondsTotal = 0.0;
    double generationSecondsMax = 0.0;  // the slowest batch
    double diskLoadSecondsTotal = 0.0;  // disk tier: reading and decoding
    double diskStoreSecondsTotal = 0.0; // disk tier: encoding and writing
};

// Thread-safe. Sizes are TerminalSet::heldBytes(): the records and the rest of their block.
//
// Pinning: a set whose shared_ptr is held outside the cache is pinned and never evicted.
// Every call trims the memory tier back to its budget, oldest unpinned entries first, so
// with nothing pinned the resident bytes never exceed the budget after a call returns.
// When pinned entries alone exceed it, the tier stays over budget (stats().pinnedBytes says
// by how much); insert() then keeps nothing new, while getOrGenerate() and find() keep the
// set they return until the caller lets go of it and a later call trims.
class TerminalSetCache {
public:
    using SetPtr = std::shared_ptr<const grammar::TerminalSet>;

    // Throws std::filesystem::filesystem_error if options.diskPath cannot be created.
    explicit TerminalSetCache(CacheOptions options);
    ~TerminalSetCache();
    TerminalSetCache(const TerminalSetCache&) = delete;
    TerminalSetCache& operator=(const TerminalSetCache&) = delete;

    // Memory, then disk (a disk hit is promoted to memory); nullptr on a miss.
    SetPtr find(const BatchKey& key);
    // The memory tier alone, for a caller that must not wait for the disk (a frame with
    // background workers): a hit counts as find()'s would; a miss is not counted, since the
    // caller goes on to getOrGenerate(), which counts it (and reads the disk there).
    SetPtr findInMemory(const BatchKey& key);
    // Into memory and, with a disk tier, queued for the disk (written on the writer's thread).
    void insert(const BatchKey& key, grammar::TerminalSet set);
    // find(), else `generate` once per key however many threads ask at the same time: the
    // others wait for it. If `generate` throws, every waiter gets the exception and nothing
    // is cached.
    SetPtr getOrGenerate(const BatchKey& key, const std::function<grammar::TerminalSet()>& generate);
    // A key nothing current has any more (an edited batch's old version) is evicted before
    // every current entry; markCurrent makes a key current and most recently used again (an
    // undo back to that version). Keys not in the memory tier are ignored.
    void markSuperseded(const BatchKey& key);
    void markCurrent(const BatchKey& key);
    // Evicts entries unpinned since the last call, if the memory tier is over budget.
    void trim();
    // Returns once every set queued for the disk tier so far is written, then trims: new sets
    // go to disk on a thread of their own, and stay pinned in memory until then.
    void flushDisk();
    CacheStats stats() const;

private:
    struct Entry {
        SetPtr set;
        uint64_t bytes = 0;
        RecencyList<BatchKey>::Position lru;
    };

    SetPtr findInMemoryLocked(const BatchKey& key);
    SetPtr promoteFromDisk(const BatchKey& key);
    // `ours` is a set only this call holds besides the cache: it does not count as a pin.
    void insertLocked(const BatchKey& key, const SetPtr& set, const grammar::TerminalSet* ours);
    void trimLocked(const grammar::TerminalSet* ours);

    CacheOptions options_;
    std::unique_ptr<DiskTier> disk_;
    std::unique_ptr<DiskWriter> writer_; // after disk_: destroyed first, writing what is queued
    mutable std::mutex mutex_;
    std::unordered_map<BatchKey, Entry, BatchKeyHash> entries_;
    RecencyList<BatchKey> lru_;
    std::unordered_map<BatchKey, std::shared_future<SetPtr>, BatchKeyHash> generating_;
    CacheStats stats_; // disk fields are filled from the disk tier in stats()
};

} // namespace hexlod::cache
