// The disk tier's writer: encodes and writes sets on a thread of its own, so the thread that
// generated a set (in a walk, often the frame's own) does not wait for zstd and the file
// system. The writer holds each queued set until it is written, so the memory tier cannot
// evict an entry it still has to write (a set the tier dropped before it was queued, being
// over budget, is written all the same). A write that fails counts as one in the tier's stats.
#pragma once

#include "disk_tier.h"

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>

namespace hexlod::cache {

class DiskWriter {
public:
    using SetPtr = std::shared_ptr<const grammar::TerminalSet>;

    // enqueue() blocks while sets of more than `maxPendingBytes` wait (one set always fits), so
    // a generator faster than the disk is slowed down rather than piling up memory.
    DiskWriter(DiskTier& tier, uint64_t maxPendingBytes);
    // Writes whatever is still queued, then stops.
    ~DiskWriter();
    DiskWriter(const DiskWriter&) = delete;
    DiskWriter& operator=(const DiskWriter&) = delete;

    void enqueue(const BatchKey& key, SetPtr set);
    // Returns once the queue is empty and no write is in progress: every set enqueued before
    // the call is on disk (or its write failed), and so may later ones be.
    void flush();

private:
    struct Job {
        BatchKey key;
        SetPtr set;
    };

    void run();

    DiskTier& tier_;
    uint64_t maxPendingBytes_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<Job> queue_;
    uint64_t pendingBytes_ = 0; // queued and being written
    uint64_t writing_ = 0;      // jobs taken off the queue, not yet written
    bool stopping_ = false;
    std::thread thread_; // last: starts once the members above exist
};

} // namespace hexlod::cache
