// Bounded, deduplicating background work for content misses: at most `workers` jobs run at
// once, at most `queueBound` distinct jobs wait, and every request for a job already queued
// or running joins it instead of starting another. Waiting requests hold no thread: their
// completions are called when the job ends, so a burst of requests for one missing batch
// costs one generation and no blocked I/O thread.
#pragma once

#include "hexlod/server/payload_cache.h"

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

namespace hexlod::server {

struct PayloadOutcome {
    PayloadBytes bytes; // set when status is 200
    int status = 200;   // else an HTTP error status with `error`
    std::string error;
    std::string current; // 404 for a stale key: the batch's current content URL
};

struct GenerationPoolStats {
    uint64_t started = 0, joined = 0, rejected = 0, completed = 0;
    uint32_t running = 0, queued = 0;
};

class GenerationPool {
public:
    enum class Admission { Started, Joined, Rejected };
    using Work = std::function<PayloadOutcome()>;
    using Done = std::function<void(const PayloadOutcome&)>;

    GenerationPool(uint32_t workers, uint32_t queueBound);
    ~GenerationPool();
    GenerationPool(const GenerationPool&) = delete;
    GenerationPool& operator=(const GenerationPool&) = delete;

    // Rejected (and `done` never called) when the queue is full or the pool is stopping.
    // `work` runs on a pool thread; an exception it throws becomes a 500 outcome.
    Admission submit(uint64_t key, Work work, Done done);
    // Queued jobs complete with 503, running ones finish (stop() waits for them), later
    // submissions are rejected.
    void stop();
    GenerationPoolStats stats() const;

private:
    struct Flight {
        Work work;
        std::vector<Done> waiters;
    };
    void workerLoop();

    const uint32_t queueBound_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<uint64_t> queue_;
    std::unordered_map<uint64_t, Flight> flights_;
    GenerationPoolStats stats_;
    bool stopping_ = false;
    std::vector<std::thread> threads_;
};

} // namespace hexlod::server
