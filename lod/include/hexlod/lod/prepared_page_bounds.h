// Page bounds computed where a terminal set is read or generated, off the frame: the
// scheduler's background thread (SchedulerOptions::onBackgroundSet) prepares them, and the
// frame that uploads the set takes them (TerminalArena::acquire) instead of computing them
// itself. On the thesis rooftop flight the bounds were 70 % of the frames' upload time. The
// background thread runs on the core the frame leaves idle while it culls and uploads.
#pragma once

#include "hexlod/grammar/terminal_set.h"
#include "hexlod/lod/page_bounds.h"

#include <cstdint>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

namespace hexlod::lod {

class PreparedPageBounds {
public:
    // Computes `set`'s page bounds and keeps them under `key` (the set's cache key digest)
    // for as long as the set lives. Thread-safe; never throws (without memory, nothing is kept).
    void prepare(uint64_t key, const std::shared_ptr<const grammar::TerminalSet>& set) noexcept;
    // The bounds prepared under `key`, handed over (and forgotten); empty when none were, and
    // the caller computes them (TerminalArena::acquire also does where their count does not fit
    // the set). Thread-safe.
    std::vector<PageBounds> take(uint64_t key);
    // Sets whose bounds are held, not uploaded yet, and those bounds' bytes.
    size_t size() const;
    uint64_t byteSize() const;

private:
    struct Entry {
        std::weak_ptr<const grammar::TerminalSet> set; // the bounds go when it does
        std::vector<PageBounds> bounds;
    };
    // Drops the entries whose set the cache let go of; the caller holds the mutex.
    void dropExpired();

    mutable std::mutex mutex_;
    std::unordered_map<uint64_t, Entry> entries_;
    uint64_t bytes_ = 0;
};

} // namespace hexlod::lod
