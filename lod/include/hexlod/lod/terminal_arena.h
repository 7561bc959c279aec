// GPU residency of terminal sets (thesis §7.5.2): one buffer of fixed capacity, allocated at
// start, that holds the records of the batches being drawn. It is divided into pages of
// HEXLOD_ARENA_PAGE records, one cull workgroup each, so a batch needs free pages but never a
// contiguous run of them and the arena never fragments. Batches are uploaded once when they
// become ready and stay until space is needed; the least recently drawn go first. Nothing is
// reallocated per frame, and records are uploaded exactly as the cache holds them.
#pragma once

#include "hexlod/grammar/terminal_set.h"
#include "hexlod/lod/page_bounds.h"

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace hexlod::lod {

inline constexpr uint32_t kArenaPageRecords = 64; // HEXLOD_ARENA_PAGE in cull_shared.h

struct ArenaStats {
    uint64_t capacityRecords = 0;
    uint64_t requestedRecords = 0; // what create() was asked for: more than capacity when the GL caps it
    uint64_t residentRecords = 0;
    uint32_t residentBatches = 0;
    uint32_t freePages = 0;
    uint32_t uploads = 0;         // since the last beginFrame()
    uint64_t uploadedBytes = 0;   // since the last beginFrame()
    uint64_t evictions = 0;       // in total
    uint32_t rejected = 0;        // since the last beginFrame(): batches that did not fit
    uint32_t preparedUploads = 0; // since the last beginFrame(): uploads with bounds prepared off the frame
    // The resident batches' page lists and page bounds (ArenaBatch), held on the CPU beside
    // the buffer: about 90 bytes a page of 64 records.
    uint64_t pageTableBytes = 0;
};

// A batch resident in the arena.
struct ArenaBatch {
    std::vector<uint32_t> pages;    // first record of each page
    std::vector<PageBounds> bounds; // each page's, for culling it whole
};

class TerminalArena {
public:
    TerminalArena() = default;
    ~TerminalArena();
    TerminalArena(const TerminalArena&) = delete;
    TerminalArena& operator=(const TerminalArena&) = delete;

    // Allocates the buffer, rounded up to whole pages; false with a reason when GL refuses.
    // The cull pass binds the whole arena as one shader storage block, so the capacity is
    // capped at GL_MAX_SHADER_STORAGE_BLOCK_SIZE (128 MiB, 4 M records, on llvmpipe): past it
    // a shader reads nothing, and terminals would vanish from the frame without an error.
    bool create(uint64_t capacityRecords, std::string& error);

    void beginFrame(uint64_t frame);
    // The pages holding `key`'s set (its records in order, kArenaPageRecords per page, the
    // last page partly filled) and their bounds, uploading it if it is not resident. To make
    // room it evicts batches not used in the current frame, oldest use first; null when even
    // that is not enough (the frame then draws the batch at a coarser LOD). The pointer stays
    // valid until the batch is evicted, which no acquire() of the same frame does. An upload
    // takes `prepared` as the set's page bounds when they are as many as its pages
    // (PreparedPageBounds), and computes them otherwise.
    const ArenaBatch* acquire(uint64_t key, const grammar::TerminalSet& set,
                              std::vector<PageBounds> prepared = {});
    bool resident(uint64_t key) const { return slots_.count(key) != 0; }

    uint32_t buffer() const { return buffer_; }
    uint64_t byteSize() const {
        return uint64_t(pageCount_) * kArenaPageRecords * sizeof(grammar::TerminalRecord);
    }
    ArenaStats stats() const;

private:
    struct Slot {
        ArenaBatch batch;
        uint64_t records = 0;
        uint64_t lastUsed = 0;
    };
    bool evictOne();

    uint32_t buffer_ = 0;
    uint32_t pageCount_ = 0;
    uint64_t frame_ = 0;
    std::unordered_map<uint64_t, Slot> slots_;
    std::vector<uint32_t> free_; // first records of free pages, lowest on top
    ArenaStats stats_;
};

} // namespace hexlod::lod
