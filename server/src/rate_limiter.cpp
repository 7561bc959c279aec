#include "hexlod/server/rate_limiter.h"

#include <algorithm>
#include <cmath>

namespace hexlod::server {

uint32_t RateLimiter::acquire(const std::string& client, Clock::time_point now) {
    if (rate_ <= 0.0) return 0;
    std::lock_guard lock(mutex_);
    if (buckets_.size() >= kMaxClients && !buckets_.contains(client)) {
        // A full bucket is what a new client starts with, so dropping those loses nothing.
        std::erase_if(buckets_, [&](const auto& entry) {
            const double seconds = std::chrono::duration<double>(now - entry.second.updated).count();
            return entry.second.tokens + seconds * rate_ >= burst_;
        });
    }
    auto [it, added] = buckets_.try_emplace(client, Bucket{burst_, now});
    Bucket& bucket = it->second;
    if (!added) {
        const double seconds = std::max(0.0, std::chrono::duration<double>(now - bucket.updated).count());
        bucket.tokens = std::min(burst_, bucket.tokens + seconds * rate_);
        bucket.updated = now;
    }
    if (bucket.tokens >= 1.0) {
        bucket.tokens -= 1.0;
        return 0;
    }
    return static_cast<uint32_t>(std::max(1.0, std::ceil((1.0 - bucket.tokens) / rate_)));
}

} // namespace hexlod::server
