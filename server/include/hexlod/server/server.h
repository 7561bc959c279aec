// The HTTP/1.1 service (ARCHITECTURE.md §7) over Boost.Beast: asynchronous keep-alive
// connections on an io_context run by a small thread pool, so idle or slow clients cost a
// socket and a timer, never a thread. Safe defaults: loopback bind; a token for edits when
// bound elsewhere; header, body and time limits; a per-client rate limit; graceful shutdown.
#pragma once

#include "hexlod/server/scene_service.h"

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace hexlod::server {

struct ServerOptions {
    std::string bind = "127.0.0.1";
    uint16_t port = 8080; // 0: any free port (see Server::port())
    uint32_t threads = 2; // I/O threads
    std::string token;    // edit token; required when `bind` is not a loopback address
    std::string webRoot = "web/dist";
    size_t maxHeaderBytes = 16 * 1024;
    size_t maxBodyBytes = 64 * 1024;
    // A request must arrive complete within this of the connection opening or the previous
    // reply (keep-alive idle time included), or the connection is closed (408 if part of it came).
    std::chrono::milliseconds requestTimeout{15000};
    std::chrono::milliseconds writeTimeout{30000}; // per reply, and per event-stream frame
    double rateLimit = 1000.0;                     // requests per second per client address; 0: no limit
    double rateBurst = 2000.0;
    uint32_t maxConnections = 4096;               // beyond: 503 and close
    std::chrono::milliseconds heartbeat{15000};   // event-stream comment interval
    size_t eventQueueFrames = 256;                // per event-stream client; beyond: dropped
    int eventSendBufferBytes = 64 * 1024;         // kernel send buffer per event stream: bounds what a
                                                  // stalled client holds besides its queue
    std::chrono::milliseconds drainTimeout{5000}; // graceful shutdown: time given to open requests
    std::function<void(const std::string&)> log;  // operational messages; none when empty
};

bool isLoopbackAddress(const std::string& address);
// Binding to any non-loopback address needs a token; false with a message saying so.
bool checkBindPolicy(const ServerOptions& options, std::string& error);

class Server {
public:
    Server(SceneService& service, ServerOptions options);
    ~Server(); // stops
    Server(const Server&) = delete;
    Server& operator=(const Server&) = delete;

    // Binds and starts serving; false with `error` when the address cannot be used.
    bool start(std::string& error);
    uint16_t port() const;   // the real port, also with ServerOptions::port = 0
    std::string url() const; // "http://127.0.0.1:8080/"
    void stopOnSignals();    // SIGINT and SIGTERM make waitForStop() return
    // Blocks until a signal (after stopOnSignals) or requestStop(), then stops gracefully.
    void waitForStop();
    void requestStop();
    // Graceful stop: no new connections, event streams closed, open requests given
    // drainTimeout to finish, then the threads end. Idempotent; call from outside the server.
    void stop();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace hexlod::server
