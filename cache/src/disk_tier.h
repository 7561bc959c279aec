// The cache's disk tier: one file per key, named by the key's digest, holding a small
// header (magic, version, the full key, the codec's checksum) and the codec's payload.
// Files are written to a temporary name and renamed, so a reader sees a whole file or
// none; whatever fails to parse is deleted and answered as a miss, so the caller
// regenerates. One process per folder: files another process writes meanwhile are not seen.
#pragma once

#include "hexlod/cache/batch_key.h"
#include "hexlod/grammar/terminal_set.h"

#include <cstdint>
#include <filesystem>
#include <list>
#include <mutex>
#include <optional>
#include <unordered_map>

namespace hexlod::cache {

inline constexpr uint32_t kDiskFileVersion = 1;
inline constexpr size_t kDiskFileHeaderBytes = 56;

struct DiskTierStats {
    uint64_t bytes = 0;
    uint64_t files = 0;
    uint64_t evictions = 0;
    uint64_t corruptFilesDropped = 0;
    uint64_t writeFailures = 0;
    double loadSeconds = 0.0;  // reading and decoding, hits and misses alike
    double storeSeconds = 0.0; // encoding and writing
};

class DiskTier {
public:
    // Creates `folder` if needed (throws std::filesystem::filesystem_error if it cannot),
    // adopts the valid files already there, deletes broken ones and leftover temporary
    // files, and evicts down to the budget. Files of other names are left alone.
    DiskTier(std::filesystem::path folder, uint64_t budgetBytes, int zstdLevel);

    // nullopt on a miss; a file that is truncated, corrupt, of another version or of
    // another key is deleted and counted.
    std::optional<grammar::TerminalSet> load(const BatchKey& key);
    void store(const BatchKey& key, const grammar::TerminalSet& set);
    void countWriteFailure();
    DiskTierStats stats() const;
    std::filesystem::path pathOf(const BatchKey& key) const;

private:
    struct File {
        uint64_t bytes = 0;
        uint64_t generation = 0; // tells a file apart from the one that replaced it
        std::list<uint64_t>::iterator lru;
    };

    void adoptExisting();
    void registerLocked(uint64_t digest, uint64_t bytes);
    void eraseLocked(uint64_t digest, bool unlink);
    void evictOverBudgetLocked();
    std::filesystem::path pathOf(uint64_t digest) const;

    std::filesystem::path folder_;
    uint64_t budgetBytes_;
    int zstdLevel_;
    mutable std::mutex mutex_;
    std::unordered_map<uint64_t, File> files_; // by key digest
    std::list<uint64_t> lru_;                  // most recently used first
    uint64_t nextGeneration_ = 1;
    uint64_t nextTemporary_ = 0;
    DiskTierStats stats_;
};

} // namespace hexlod::cache
