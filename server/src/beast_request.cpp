#include "hexlod/server/beast_request.h"

#include <cctype>

namespace hexlod::server {

namespace http = boost::beast::http;

std::optional<Reply> rejectBeforeRouting(const BeastRequest& message) {
    if (message.version() != 10 && message.version() != 11) {
        Reply r = errorReply(505, "only HTTP/1.0 and HTTP/1.1 are spoken here");
        r.closeConnection = true;
        return r;
    }
    // Host is mandatory in HTTP/1.1 (RFC 9112 §3.2); it is asked of HTTP/1.0 too, so that a
    // reply never depends on a client's guess at the service's name.
    const auto host = message.find(http::field::host);
    if (host == message.end() || host->value().empty()) {
        Reply r = errorReply(400, "missing Host header");
        r.closeConnection = true;
        return r;
    }
    return std::nullopt;
}

Request toRequest(BeastRequest&& message, std::string remoteAddress) {
    Request request;
    const auto text = [](boost::beast::string_view s) { return std::string(s.data(), s.size()); };
    request.method = text(message.method_string());
    request.target = text(message.target());
    request.version = message.version();
    for (const auto& field : message) {
        std::string name = text(field.name_string());
        for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        request.headers.emplace_back(std::move(name), text(field.value()));
    }
    request.body = std::move(message.body());
    request.remoteAddress = std::move(remoteAddress);
    return request;
}

} // namespace hexlod::server
