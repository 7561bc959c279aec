#include "disk_writer.h"

namespace hexlod::cache {

DiskWriter::DiskWriter(DiskTier& tier, uint64_t maxPendingBytes)
    : tier_(tier), maxPendingBytes_(maxPendingBytes), thread_([this] { run(); }) {}

DiskWriter::~DiskWriter() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    changed_.notify_all();
    thread_.join();
}

void DiskWriter::enqueue(const BatchKey& key, SetPtr set) {
    const uint64_t bytes = set->byteSize();
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return pendingBytes_ == 0 || pendingBytes_ + bytes <= maxPendingBytes_; });
    pendingBytes_ += bytes;
    queue_.push_back({key, std::move(set)});
    changed_.notify_all();
}

void DiskWriter::flush() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return queue_.empty() && writing_ == 0; });
}

void DiskWriter::run() {
    std::unique_lock lock(mutex_);
    for (;;) {
        changed_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
        if (queue_.empty()) return; // stopping, with everything written
        Job job = std::move(queue_.front());
        queue_.pop_front();
        ++writing_;
        lock.unlock();
        try {
            tier_.store(job.key, *job.set);
        } catch (...) {
            tier_.countWriteFailure(); // out of memory while encoding: the set stays in memory only
        }
        const uint64_t bytes = job.set->byteSize();
        job.set.reset(); // unpinned before anyone waiting on flush() looks at the cache
        lock.lock();
        --writing_;
        pendingBytes_ -= bytes;
        changed_.notify_all();
    }
}

} // namespace hexlod::cache
