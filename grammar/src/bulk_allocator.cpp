#include "hexlod/grammar/bulk_allocator.h"

#include <iterator>
#include <map>
#include <mutex>
#include <unordered_map>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace hexlod::grammar::detail {
namespace {

// Released blocks wait here for the next batch instead of going back to the kernel, which
// would hand out fresh pages that it must zero again: in steady state (cells expanded and
// evicted all the time) that zeroing cost more than the expansion itself. Bounded, so a
// one-off giant batch does not pin its memory forever.
constexpr size_t kDefaultRetainedBytes = size_t(2) << 30;

// A request takes the smallest released block that holds it, if that block is at most this
// fraction larger. Sets decoded from the disk tier come in every size, so a pool that matched
// sizes exactly missed most of them: it kept the blocks of the sets the cache evicted while
// every decode page-faulted a fresh one (docs/BENCHMARKS.md, "Released blocks reused at any
// size close enough"). The bound caps the memory a set holds beyond its records.
constexpr size_t kMaxSlackDivisor = 4; // a quarter

class BlockPool {
public:
    // A released block of at least `bytes`, or nullptr.
    void* take(size_t bytes) {
        std::lock_guard lock(mutex_);
        const auto it = free_.lower_bound(bytes);
        if (it == free_.end() || it->first > bytes + bytes / kMaxSlackDivisor) return nullptr;
        void* pointer = it->second;
        inUse_.emplace(pointer, it->first);
        retained_ -= it->first;
        free_.erase(it);
        return pointer;
    }
    void track(void* pointer, size_t bytes) {
        std::lock_guard lock(mutex_);
        inUse_.emplace(pointer, bytes);
    }
    // Keeps a block handed out before, at its own size; false if the limit leaves no room (the
    // caller frees it).
    bool give(void* pointer) {
        std::lock_guard lock(mutex_);
        const auto it = inUse_.find(pointer);
        if (it == inUse_.end()) return false; // not ours: never happens, but never kept either
        const size_t bytes = it->second;
        inUse_.erase(it);
        if (retained_ + bytes > limit_) return false;
        free_.emplace(bytes, pointer);
        retained_ += bytes;
        return true;
    }
    void setLimit(size_t bytes) {
        std::lock_guard lock(mutex_);
        limit_ = bytes;
        while (retained_ > limit_) {
            const auto largest = std::prev(free_.end());
            retained_ -= largest->first;
            std::free(largest->second);
            free_.erase(largest);
        }
    }
    size_t retained() {
        std::lock_guard lock(mutex_);
        return retained_;
    }
    // The size of a block handed out, or 0 for one that is not.
    size_t sizeOf(const void* pointer) {
        std::lock_guard lock(mutex_);
        const auto it = inUse_.find(const_cast<void*>(pointer));
        return it == inUse_.end() ? 0 : it->second;
    }
    ~BlockPool() {
        for (const auto& [bytes, pointer] : free_) std::free(pointer);
    }

private:
    std::mutex mutex_;
    std::multimap<size_t, void*> free_;       // by size
    std::unordered_map<void*, size_t> inUse_; // every block handed out, with its size
    size_t retained_ = 0;
    size_t limit_ = kDefaultRetainedBytes;
};

BlockPool& pool() {
    static BlockPool instance;
    return instance;
}

size_t roundedSize(size_t bytes) {
    return (bytes + kHugePage - 1) / kHugePage * kHugePage;
}

} // namespace

void* allocateBulk(size_t bytes) {
    const size_t rounded = roundedSize(bytes);
    if (void* reused = pool().take(rounded)) return reused;
    void* pointer = std::aligned_alloc(kHugePage, rounded);
    if (!pointer) throw std::bad_alloc();
#if defined(MADV_HUGEPAGE)
    // Advice only: where huge pages are off or exhausted the kernel falls back to 4 KiB pages.
    madvise(pointer, rounded, MADV_HUGEPAGE);
#endif
    try {
        pool().track(pointer, rounded);
    } catch (...) {
        std::free(pointer);
        throw;
    }
    return pointer;
}

void releaseBulk(void* pointer) noexcept {
    if (!pool().give(pointer)) std::free(pointer);
}

} // namespace hexlod::grammar::detail

namespace hexlod::grammar {

void setBulkPoolLimit(size_t bytes) {
    detail::pool().setLimit(bytes);
}

size_t bulkPoolBytes() {
    return detail::pool().retained();
}

size_t bulkBlockBytes(const void* pointer, size_t requested) {
    if (requested < detail::kHugeThreshold) return requested;
    const size_t block = detail::pool().sizeOf(pointer);
    return block ? block : requested;
}

} // namespace hexlod::grammar
