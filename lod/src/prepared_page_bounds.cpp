#include "hexlod/lod/prepared_page_bounds.h"

#include <new>

namespace hexlod::lod {
namespace {

uint64_t bytesOf(const std::vector<PageBounds>& bounds) {
    return bounds.size() * sizeof(PageBounds);
}

} // namespace

void PreparedPageBounds::prepare(uint64_t key,
                                 const std::shared_ptr<const grammar::TerminalSet>& set) noexcept {
    if (!set) return;
    try {
        Entry entry{set, pageBounds(*set)};
        std::lock_guard lock(mutex_);
        dropExpired();
        bytes_ += bytesOf(entry.bounds);
        if (const auto it = entries_.find(key); it != entries_.end()) bytes_ -= bytesOf(it->second.bounds);
        entries_.insert_or_assign(key, std::move(entry));
    } catch (const std::bad_alloc&) {
        // The frame computes them when it uploads the set, as it would without this.
    }
}

std::vector<PageBounds> PreparedPageBounds::take(uint64_t key) {
    std::lock_guard lock(mutex_);
    dropExpired();
    const auto it = entries_.find(key);
    if (it == entries_.end()) return {};
    std::vector<PageBounds> bounds = std::move(it->second.bounds);
    bytes_ -= bytesOf(bounds);
    entries_.erase(it);
    return bounds;
}

size_t PreparedPageBounds::size() const {
    std::lock_guard lock(mutex_);
    return entries_.size();
}

uint64_t PreparedPageBounds::byteSize() const {
    std::lock_guard lock(mutex_);
    return bytes_;
}

void PreparedPageBounds::dropExpired() {
    std::erase_if(entries_, [this](const auto& entry) {
        const bool expired = entry.second.set.expired();
        if (expired) bytes_ -= bytesOf(entry.second.bounds);
        return expired;
    });
}

} // namespace hexlod::lod
