// What every connection of the server shares: options, the API, the rate limiter, the
// metrics and the registry of open connections that a graceful stop walks.
#pragma once

#include "hexlod/server/rate_limiter.h"
#include "hexlod/server/server.h"
#include "hexlod/server/service_api.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <unordered_map>

namespace hexlod::server {

// A connection a graceful stop can ask to finish: close when idle, else after its reply.
class Connection {
public:
    virtual ~Connection() = default;
    virtual void shutdown() = 0;
};

class ConnectionRegistry {
public:
    uint64_t add(std::weak_ptr<Connection> connection);
    void remove(uint64_t id);
    void shutdownAll();
    size_t size() const;

private:
    mutable std::mutex mutex_;
    uint64_t next_ = 1;
    std::unordered_map<uint64_t, std::weak_ptr<Connection>> connections_;
};

// Counts an open TCP connection for as long as it lives; moves from the HTTP session to the
// event stream it turns into.
class OpenConnection {
public:
    explicit OpenConnection(Metrics& metrics) : metrics_(metrics) { ++metrics_.connectionsOpen; }
    ~OpenConnection() { --metrics_.connectionsOpen; }
    OpenConnection(const OpenConnection&) = delete;
    OpenConnection& operator=(const OpenConnection&) = delete;

private:
    Metrics& metrics_;
};

struct ServerContext {
    const ServerOptions& options;
    const ServiceApi& api;
    SceneService& service;
    RateLimiter limiter;
    ConnectionRegistry connections;
    std::atomic<bool> stopping{false};
};

} // namespace hexlod::server
