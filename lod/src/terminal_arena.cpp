// Paged allocation over a fixed GL buffer, with LRU eviction of whole batches.
#include "hexlod/lod/terminal_arena.h"
#include "hexlod/lod/page_bounds.h"
#include "hexlod/render/gl_api.h"

#include <algorithm>
#include <limits>

namespace hexlod::lod {
namespace {

// What a resident batch holds on the CPU beside its records in the buffer.
uint64_t pageTableBytes(const ArenaBatch& batch) {
    return batch.pages.size() * sizeof(uint32_t) + batch.bounds.size() * sizeof(PageBounds);
}

} // namespace

TerminalArena::~TerminalArena() {
    if (buffer_) gl::glDeleteBuffers(1, &buffer_);
}

bool TerminalArena::create(uint64_t capacityRecords, std::string& error) {
    GLint64 maxBlockBytes = 0;
    gl::glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlockBytes);
    const uint64_t maxPages = uint64_t(maxBlockBytes) / (kArenaPageRecords * sizeof(grammar::TerminalRecord));
    const uint64_t pages = std::min((capacityRecords + kArenaPageRecords - 1) / kArenaPageRecords, maxPages);
    if (pages == 0 || pages * kArenaPageRecords > std::numeric_limits<uint32_t>::max()) {
        error =
            "terminal arena capacity " + std::to_string(capacityRecords) + " records is outside [1, 2^32)";
        return false;
    }
    gl::glCreateBuffers(1, &buffer_);
    gl::glNamedBufferStorage(buffer_, GLsizeiptr(pages * kArenaPageRecords * sizeof(grammar::TerminalRecord)),
                             nullptr, GL_DYNAMIC_STORAGE_BIT);
    if (gl::glGetError() != GL_NO_ERROR) {
        error = "cannot allocate a terminal arena of " +
                std::to_string(pages * kArenaPageRecords * 32 >> 20) + " MiB";
        gl::glDeleteBuffers(1, &buffer_);
        buffer_ = 0;
        return false;
    }
    pageCount_ = uint32_t(pages);
    free_.clear();
    // Lowest pages on top of the stack: fresh batches land in one contiguous run, one upload.
    for (uint32_t p = pageCount_; p-- > 0;) free_.push_back(p * kArenaPageRecords);
    slots_.clear();
    stats_ = {};
    stats_.capacityRecords = pages * kArenaPageRecords;
    stats_.requestedRecords = capacityRecords;
    return true;
}

void TerminalArena::beginFrame(uint64_t frame) {
    frame_ = frame;
    stats_.uploads = 0;
    stats_.uploadedBytes = 0;
    stats_.rejected = 0;
    stats_.preparedUploads = 0;
}

bool TerminalArena::evictOne() {
    auto oldest = slots_.end();
    for (auto it = slots_.begin(); it != slots_.end(); ++it) {
        if (it->second.lastUsed >= frame_) continue; // drawn this frame: keep
        if (oldest == slots_.end() || it->second.lastUsed < oldest->second.lastUsed) oldest = it;
    }
    if (oldest == slots_.end()) return false;
    // Freed pages go back in descending order so the lowest is reused first.
    stats_.pageTableBytes -= pageTableBytes(oldest->second.batch);
    std::vector<uint32_t> pages = std::move(oldest->second.batch.pages);
    std::sort(pages.begin(), pages.end(), std::greater<>());
    free_.insert(free_.end(), pages.begin(), pages.end());
    stats_.residentRecords -= oldest->second.records;
    slots_.erase(oldest);
    ++stats_.evictions;
    return true;
}

const ArenaBatch* TerminalArena::acquire(uint64_t key, const grammar::TerminalSet& set,
                                         std::vector<PageBounds> prepared) {
    if (auto it = slots_.find(key); it != slots_.end()) {
        it->second.lastUsed = frame_;
        return &it->second.batch;
    }
    const uint64_t records = set.records.size();
    const uint64_t needed = (records + kArenaPageRecords - 1) / kArenaPageRecords;
    if (needed > pageCount_) {
        ++stats_.rejected;
        return nullptr;
    }
    while (free_.size() < needed && evictOne()) {}
    if (free_.size() < needed) {
        ++stats_.rejected;
        return nullptr;
    }
    Slot slot;
    slot.records = records;
    slot.lastUsed = frame_;
    std::vector<uint32_t>& pages = slot.batch.pages;
    for (uint64_t p = 0; p < needed; ++p) {
        pages.push_back(free_.back());
        free_.pop_back();
    }
    // One upload per run of consecutive pages.
    for (uint64_t p = 0; p < needed;) {
        uint64_t run = 1;
        while (p + run < needed && pages[p + run] == pages[p] + run * kArenaPageRecords) ++run;
        const uint64_t first = p * kArenaPageRecords,
                       count = std::min(records - first, run * kArenaPageRecords);
        gl::glNamedBufferSubData(buffer_, GLintptr(uint64_t(pages[p]) * sizeof(grammar::TerminalRecord)),
                                 GLsizeiptr(count * sizeof(grammar::TerminalRecord)),
                                 set.records.data() + first);
        p += run;
    }
    const bool usePrepared = needed > 0 && prepared.size() == needed;
    slot.batch.bounds = usePrepared ? std::move(prepared) : pageBounds(set);
    stats_.preparedUploads += usePrepared;
    stats_.pageTableBytes += pageTableBytes(slot.batch);
    stats_.residentRecords += records;
    ++stats_.uploads;
    stats_.uploadedBytes += records * sizeof(grammar::TerminalRecord);
    return &(slots_[key] = std::move(slot)).batch;
}

ArenaStats TerminalArena::stats() const {
    ArenaStats s = stats_;
    s.residentBatches = uint32_t(slots_.size());
    s.freePages = uint32_t(free_.size());
    return s;
}

} // namespace hexlod::lod
