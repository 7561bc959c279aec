#include "hexlod/server/router.h"

#include <algorithm>

namespace hexlod::server {
namespace {

std::vector<std::string> splitPattern(const std::string& pattern) {
    std::vector<std::string> segments;
    size_t start = 1;
    while (start <= pattern.size()) {
        const size_t slash = pattern.find('/', start);
        segments.push_back(
            pattern.substr(start, slash == std::string::npos ? std::string::npos : slash - start));
        if (slash == std::string::npos) break;
        start = slash + 1;
    }
    return segments;
}

bool isParameter(const std::string& segment) {
    return segment.size() >= 2 && segment.front() == '{' && segment.back() == '}';
}

bool matches(const std::vector<std::string>& pattern, const std::vector<std::string>& path,
             std::vector<std::string_view>& params) {
    if (pattern.size() != path.size()) return false;
    params.clear();
    for (size_t i = 0; i < pattern.size(); ++i) {
        if (isParameter(pattern[i])) {
            if (path[i].empty()) return false;
            params.push_back(path[i]);
        } else if (pattern[i] != path[i]) {
            return false;
        }
    }
    return true;
}

// Compares in time independent of where the strings first differ.
bool sameSecret(std::string_view a, std::string_view b) {
    unsigned char difference = a.size() == b.size() ? 0 : 1;
    const size_t n = std::max(a.size(), b.size());
    for (size_t i = 0; i < n; ++i)
        difference |= static_cast<unsigned char>((i < a.size() ? a[i] : 0) ^ (i < b.size() ? b[i] : 0));
    return difference == 0;
}

} // namespace

void Router::add(std::string method, std::string pattern, Handler handler, bool needsToken) {
    std::vector<std::string> segments = splitPattern(pattern);
    routes_.push_back(
        {std::move(method), std::move(pattern), std::move(segments), std::move(handler), needsToken});
}

bool Router::authorised(const Request& request, Respond& respond) const {
    if (token_.empty()) return true;
    const auto header = request.header("authorization");
    if (!header) {
        Reply reply =
            errorReply(401, "this service needs a token for edits: send 'Authorization: Bearer <token>'");
        reply.set("WWW-Authenticate", "Bearer realm=\"hexlod\"");
        respond(std::move(reply));
        return false;
    }
    constexpr std::string_view scheme = "Bearer ";
    if (header->size() <= scheme.size() || header->substr(0, scheme.size()) != scheme ||
        !sameSecret(header->substr(scheme.size()), token_)) {
        respond(errorReply(403, "the edit token is wrong"));
        return false;
    }
    return true;
}

std::string Router::dispatch(const Request& request, Respond respond) const {
    ParsedTarget target;
    std::string error;
    if (!parseTarget(request.target, target, error)) {
        respond(
            errorReply(target.path.empty() && request.target.size() > kMaxTargetBytes ? 414 : 400, error));
        return "unmatched";
    }
    const bool head = request.method == "HEAD";
    const std::string& method = head ? std::string("GET") : request.method;
    std::vector<std::string_view> params;
    std::string allowed;
    for (const Route& route : routes_) {
        if (!matches(route.segments, target.segments, params)) continue;
        if (route.method != method) {
            if (allowed.find(route.method) == std::string::npos)
                allowed +=
                    (allowed.empty() ? "" : ", ") + route.method + (route.method == "GET" ? ", HEAD" : "");
            continue;
        }
        const std::string name = route.method + " " + route.pattern;
        if (route.needsToken && !authorised(request, respond)) return name;
        if (method == "GET" && !target.segments.empty() && target.segments[0] == "api") {
            // Reads may come from any origin (a viewer served elsewhere, a dev server): the data
            // is public and read-only. Writes get no such header, so a browser keeps other
            // origins' pages from posting edits (their JSON body needs a CORS preflight).
            respond = [inner = std::move(respond)](Reply reply) {
                reply.set("Access-Control-Allow-Origin", "*");
                inner(std::move(reply));
            };
        }
        route.handler(RequestContext{request, target, params, head}, std::move(respond));
        return name;
    }
    if (!allowed.empty()) {
        Reply reply = errorReply(405, "method " + request.method + " is not allowed here; use " + allowed);
        reply.set("Allow", allowed);
        respond(std::move(reply));
        return "unmatched";
    }
    const bool api = !target.segments.empty() && target.segments[0] == "api";
    if (api || !fallback_) {
        const bool otherVersion = api && target.segments.size() > 1 && target.segments[1] != "v1";
        respond(errorReply(404, otherVersion ? "unknown API version: this service speaks /api/v1"
                                             : "no such resource: " + target.path + " (see /api/v1/scene)"));
        return "unmatched";
    }
    if (method != "GET") {
        Reply reply = errorReply(405, "method " + request.method + " is not allowed here; use GET, HEAD");
        reply.set("Allow", "GET, HEAD");
        respond(std::move(reply));
        return "unmatched";
    }
    fallback_(RequestContext{request, target, {}, head}, std::move(respond));
    return "static";
}

} // namespace hexlod::server
