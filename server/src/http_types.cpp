#include "hexlod/server/http_types.h"

#include <nlohmann/json.hpp>

namespace hexlod::server {

std::optional<std::string_view> Request::header(std::string_view lowerName) const {
    for (const auto& [name, value] : headers)
        if (name == lowerName) return std::string_view(value);
    return std::nullopt;
}

std::string jsonText(const nlohmann::json& value) {
    return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

Reply jsonReply(int status, std::string json) {
    Reply reply;
    reply.status = status;
    reply.contentType = "application/json";
    reply.body = std::move(json);
    return reply;
}

Reply errorReply(int status, const std::string& reason, const std::string& field) {
    nlohmann::json body = {{"status", status}, {"error", reason}};
    if (!field.empty()) body["field"] = field;
    Reply reply = jsonReply(status, jsonText(body) + "\n");
    // Errors describe the state at the time of asking: never cache them.
    reply.set("Cache-Control", "no-store");
    return reply;
}

const char* reasonPhrase(int status) {
    switch (status) {
    case 200:
        return "OK";
    case 204:
        return "No Content";
    case 304:
        return "Not Modified";
    case 400:
        return "Bad Request";
    case 401:
        return "Unauthorized";
    case 403:
        return "Forbidden";
    case 404:
        return "Not Found";
    case 405:
        return "Method Not Allowed";
    case 408:
        return "Request Timeout";
    case 409:
        return "Conflict";
    case 410:
        return "Gone";
    case 411:
        return "Length Required";
    case 413:
        return "Content Too Large";
    case 414:
        return "URI Too Long";
    case 415:
        return "Unsupported Media Type";
    case 429:
        return "Too Many Requests";
    case 431:
        return "Request Header Fields Too Large";
    case 500:
        return "Internal Server Error";
    case 501:
        return "Not Implemented";
    case 503:
        return "Service Unavailable";
    case 505:
        return "HTTP Version Not Supported";
    default:
        return "Unknown";
    }
}

} // namespace hexlod::server
