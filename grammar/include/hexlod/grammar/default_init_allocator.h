// An allocator whose resize() leaves trivially constructible elements uninitialised.
// A batch's terminal array is written in full by a parallel scatter right after it is sized;
// zero-filling it first cost a single-threaded pass over hundreds of megabytes.
#pragma once

#include <memory>
#include <type_traits>
#include <utility>

namespace hexlod::grammar {

template <typename T, typename Base = std::allocator<T>> class DefaultInitAllocator : public Base {
    using Traits = std::allocator_traits<Base>;

public:
    template <typename U> struct rebind {
        using other = DefaultInitAllocator<U, typename Traits::template rebind_alloc<U>>;
    };
    using Base::Base;

    template <typename U> void construct(U* ptr) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(ptr)) U;
    }
    template <typename U, typename... Args> void construct(U* ptr, Args&&... args) {
        Traits::construct(static_cast<Base&>(*this), ptr, std::forward<Args>(args)...);
    }
};

} // namespace hexlod::grammar
