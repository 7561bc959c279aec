// Per-client request rate limit: one token bucket per remote address, `rate` tokens a
// second up to `burst`. A request without a token is answered 429 with Retry-After. Buckets
// of clients gone quiet are forgotten, so the table stays bounded.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <unordered_map>

namespace hexlod::server {

class RateLimiter {
public:
    using Clock = std::chrono::steady_clock;
    // rate == 0 disables the limit.
    RateLimiter(double rate, double burst) : rate_(rate), burst_(std::max(burst, 1.0)) {}

    // 0 when the request may go ahead, else the whole seconds to wait (at least 1).
    uint32_t acquire(const std::string& client, Clock::time_point now = Clock::now());
    bool enabled() const { return rate_ > 0.0; }

private:
    struct Bucket {
        double tokens = 0.0;
        Clock::time_point updated;
    };
    static constexpr size_t kMaxClients = 65536;

    const double rate_, burst_;
    std::mutex mutex_;
    std::unordered_map<std::string, Bucket> buckets_;
};

} // namespace hexlod::server
