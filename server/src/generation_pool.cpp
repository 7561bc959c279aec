#include "hexlod/server/generation_pool.h"

#include <algorithm>
#include <exception>

namespace hexlod::server {

GenerationPool::GenerationPool(uint32_t workers, uint32_t queueBound) : queueBound_(queueBound) {
    for (uint32_t i = 0; i < std::max(workers, 1u); ++i) threads_.emplace_back([this] { workerLoop(); });
}

GenerationPool::~GenerationPool() {
    stop();
}

GenerationPool::Admission GenerationPool::submit(uint64_t key, Work work, Done done) {
    {
        std::lock_guard lock(mutex_);
        if (stopping_) {
            ++stats_.rejected;
            return Admission::Rejected;
        }
        const auto it = flights_.find(key);
        if (it != flights_.end()) {
            it->second.waiters.push_back(std::move(done));
            ++stats_.joined;
            return Admission::Joined;
        }
        if (queue_.size() >= queueBound_) {
            ++stats_.rejected;
            return Admission::Rejected;
        }
        Flight& flight = flights_[key];
        flight.work = std::move(work);
        flight.waiters.push_back(std::move(done));
        queue_.push_back(key);
        ++stats_.started;
    }
    wake_.notify_one();
    return Admission::Started;
}

void GenerationPool::stop() {
    std::vector<Done> cancelled;
    {
        std::lock_guard lock(mutex_);
        if (stopping_) return;
        stopping_ = true;
        for (const uint64_t key : queue_) {
            for (Done& d : flights_[key].waiters) cancelled.push_back(std::move(d));
            flights_.erase(key);
        }
        queue_.clear();
    }
    wake_.notify_all();
    const PayloadOutcome outcome{nullptr, 503, "the service is shutting down", {}};
    for (Done& d : cancelled) d(outcome);
    for (std::thread& t : threads_)
        if (t.joinable() && t.get_id() != std::this_thread::get_id()) t.join();
}

GenerationPoolStats GenerationPool::stats() const {
    std::lock_guard lock(mutex_);
    GenerationPoolStats s = stats_;
    s.queued = static_cast<uint32_t>(queue_.size());
    return s;
}

void GenerationPool::workerLoop() {
    while (true) {
        uint64_t key = 0;
        Work work;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
            if (queue_.empty()) return; // stopping, and stop() completed everything queued
            key = queue_.front();
            queue_.pop_front();
            work = std::move(flights_[key].work);
            ++stats_.running;
        }
        PayloadOutcome outcome;
        try {
            outcome = work();
        } catch (const std::exception& e) {
            outcome = {nullptr, 500, std::string("generation failed: ") + e.what(), {}};
        }
        std::vector<Done> waiters;
        {
            std::lock_guard lock(mutex_);
            waiters = std::move(flights_[key].waiters);
            flights_.erase(key);
            --stats_.running;
            ++stats_.completed;
        }
        for (Done& d : waiters) d(outcome);
    }
}

} // namespace hexlod::server
