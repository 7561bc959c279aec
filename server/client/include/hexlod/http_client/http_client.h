// A small blocking HTTP/1.1 client over Boost.Beast for tests, benchmarks and tools: keep-alive
// connections, raw byte exchanges (to send malformed requests on purpose) and a
// Server-Sent Events reader. Every read has a timeout, so a misbehaving server fails a test
// instead of hanging it.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hexlod::http_client {

using Headers = std::vector<std::pair<std::string, std::string>>;

struct Response {
    int status = 0;                             // 0: no response (the connection closed or timed out)
    std::map<std::string, std::string> headers; // lower-case names
    std::string body;
    std::string header(const std::string& lowerName) const;
};

class Connection {
public:
    Connection(const std::string& host, uint16_t port,
               std::chrono::milliseconds timeout = std::chrono::milliseconds(30000)); // throws on failure
    ~Connection();
    Connection(const Connection&) = delete;
    Connection& operator=(const Connection&) = delete;

    Response request(const std::string& method, const std::string& target, const std::string& body = {},
                     const Headers& headers = {});
    Response get(const std::string& target, const Headers& headers = {}) {
        return request("GET", target, {}, headers);
    }
    Response post(const std::string& target, const std::string& body, const Headers& headers = {});
    // Sends `bytes` as they are and reads one response.
    Response raw(std::string_view bytes);
    // Reads one more response from the connection (after a pipelined raw()).
    Response readResponse();
    bool isOpen() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::string host_;
};

// One request on a connection of its own.
Response fetch(const std::string& host, uint16_t port, const std::string& method, const std::string& target,
               const std::string& body = {}, const Headers& headers = {});

struct ServerSentEvent {
    std::string id, event, data;
};

class EventStreamReader {
public:
    // receiveBufferBytes > 0 shrinks the socket's receive buffer (to play a slow client).
    EventStreamReader(const std::string& host, uint16_t port, const std::string& target,
                      const Headers& headers = {}, int receiveBufferBytes = 0);
    ~EventStreamReader();
    int status() const { return status_; }
    std::string header(const std::string& lowerName) const;
    // The next event (comments such as heartbeats are skipped), or nullopt at the timeout or
    // when the server closed the stream.
    std::optional<ServerSentEvent> next(std::chrono::milliseconds timeout);
    // Stops reading without closing: the socket's receive buffer fills (a slow client).
    void close();

private:
    bool readMore(std::chrono::steady_clock::time_point deadline);
    struct Impl;
    std::unique_ptr<Impl> impl_;
    int status_ = 0;
    std::map<std::string, std::string> headers_;
    std::string buffer_;
};

} // namespace hexlod::http_client
