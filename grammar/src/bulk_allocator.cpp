#include "hexlod/grammar/bulk_allocator.h"

#include <iterator>
#include <map>
#include <mutex>

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

class BlockPool {
public:
    void* take(size_t bytes) {
        std::lock_guard lock(mutex_);
        const auto it = free_.find(bytes);
        if (it == free_.end()) return nullptr;
        void* pointer = it->second;
        free_.erase(it);
        retained_ -= bytes;
        return pointer;
    }
    bool give(void* pointer, size_t bytes) {
        std::lock_guard lock(mutex_);
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
    ~BlockPool() {
        for (const auto& [bytes, pointer] : free_) std::free(pointer);
    }

private:
    std::mutex mutex_;
    std::multimap<size_t, void*> free_;
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
    return pointer;
}

void releaseBulk(void* pointer, size_t bytes) noexcept {
    if (!pool().give(pointer, roundedSize(bytes))) std::free(pointer);
}

} // namespace hexlod::grammar::detail

namespace hexlod::grammar {

void setBulkPoolLimit(size_t bytes) {
    detail::pool().setLimit(bytes);
}

size_t bulkPoolBytes() {
    return detail::pool().retained();
}

} // namespace hexlod::grammar
