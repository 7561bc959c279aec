// The request and reply the service's handlers see, free of Boost.Beast so that handlers,
// the router and their tests compile without it: the HTTP session (src/http_session.cpp)
// converts from and to Beast messages, and the fuzz target builds requests directly.
#pragma once

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hexlod::server {

struct Request {
    std::string method;                                       // as sent, e.g. "GET"
    std::string target;                                       // as sent, e.g. "/api/v1/cells?x=1"
    unsigned version = 11;                                    // 10 for HTTP/1.0, 11 for HTTP/1.1
    std::vector<std::pair<std::string, std::string>> headers; // names lower-cased, in order
    std::string body;
    std::string remoteAddress; // the peer's IP, for rate limits and logs

    // The first header of that (lower-case) name, or nullopt.
    std::optional<std::string_view> header(std::string_view lowerName) const;
};

// A reply's body is one of: text (`body`), shared immutable bytes (`payload`, for cached
// content, sent without a copy), a file streamed from disk (`filePath`), or an event stream
// (`eventStream`: the session becomes a Server-Sent Events stream).
struct Reply {
    int status = 200;
    std::string contentType = "application/json";
    std::vector<std::pair<std::string, std::string>> headers;
    std::string body;
    std::shared_ptr<const std::vector<uint8_t>> payload;
    std::string filePath;
    uint64_t fileBytes = 0;
    bool eventStream = false;
    std::optional<uint64_t> lastEventId; // eventStream: where the client resumes
    bool closeConnection = false;        // after this reply

    void set(std::string name, std::string value) { headers.emplace_back(std::move(name), std::move(value)); }
    uint64_t bodyBytes() const {
        return payload ? payload->size() : (filePath.empty() ? body.size() : fileBytes);
    }
};

// Handlers answer through this, on any thread, exactly once.
using Respond = std::function<void(Reply)>;

// JSON text for a reply, an event or a journal line. Strings that are not valid UTF-8 (a
// reason quoting a client's bytes) are written with U+FFFD instead of making dump() throw.
std::string jsonText(const nlohmann::json& value);

// A JSON error body: {"error": reason, "status": status[, "field": field]}.
Reply errorReply(int status, const std::string& reason, const std::string& field = {});
Reply jsonReply(int status, std::string json);

const char* reasonPhrase(int status);

} // namespace hexlod::server
