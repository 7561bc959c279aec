// The allocator of a batch's terminal array, tuned for arrays of hundreds of megabytes that
// are sized once and then written in full by a parallel scatter:
// - resize() leaves trivially constructible elements uninitialised, so no single-threaded
//   zero-fill pass runs before the scatter;
// - allocations of 4 MiB and more are 2 MiB aligned and asked to use transparent huge pages,
//   which cuts first-touch page faults 512-fold (they were a third of expansion time);
// - released large blocks are pooled (up to 2 GiB by default, setBulkPoolLimit) for the next
//   batch or decoded set, so steady-state expansion does not pay the kernel to zero fresh
//   pages again; a request takes the smallest pooled block that holds it, if that block is at
//   most a quarter larger.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>

namespace hexlod::grammar {

// Bytes of released blocks the pool may keep; a long-running service lowers it so that its
// memory stays near its cache budgets. Blocks beyond a lowered limit are freed at once.
void setBulkPoolLimit(size_t bytes);
size_t bulkPoolBytes(); // retained now

// The bytes the block behind `pointer`, allocated for `requested` bytes, holds: a bulk block's
// whole size (whole huge pages, and up to a quarter more when it reused a released block);
// `requested` for an allocation below the bulk threshold, the heap's.
size_t bulkBlockBytes(const void* pointer, size_t requested);

namespace detail {
constexpr size_t kHugePage = size_t(2) << 20;
constexpr size_t kHugeThreshold = size_t(4) << 20;
void* allocateBulk(size_t bytes);         // huge-page-backed where the kernel allows it
void releaseBulk(void* pointer) noexcept; // may keep it for reuse
} // namespace detail

template <typename T> class BulkAllocator {
public:
    using value_type = T;
    BulkAllocator() = default;
    template <typename U> BulkAllocator(const BulkAllocator<U>&) noexcept {}

    T* allocate(size_t n) {
        const size_t bytes = n * sizeof(T);
        if (bytes >= detail::kHugeThreshold) return static_cast<T*>(detail::allocateBulk(bytes));
        return std::allocator<T>().allocate(n);
    }
    void deallocate(T* pointer, size_t n) noexcept {
        if (n * sizeof(T) >= detail::kHugeThreshold) return detail::releaseBulk(pointer);
        std::allocator<T>().deallocate(pointer, n);
    }

    template <typename U> void construct(U* pointer) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(pointer)) U;
    }
    template <typename U, typename... Args> void construct(U* pointer, Args&&... args) {
        ::new (static_cast<void*>(pointer)) U(std::forward<Args>(args)...);
    }

    template <typename U> bool operator==(const BulkAllocator<U>&) const noexcept { return true; }
};

} // namespace hexlod::grammar
