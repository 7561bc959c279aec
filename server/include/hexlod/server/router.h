// The route table: method and path pattern to handler. Patterns are literal segments and
// "{name}" parameters ("/api/v1/terminal-sets/{cell}/{grammar}/{key}"). This is where
// other modules plug their endpoints in (terminal meshes, impostors): add() a route.
#pragma once

#include "hexlod/server/http_target.h"
#include "hexlod/server/http_types.h"

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace hexlod::server {

struct RequestContext {
    const Request& request;
    const ParsedTarget& target;
    std::vector<std::string_view> params; // the pattern's {parameters}, in order
    bool head = false;                    // a HEAD request routed to its GET handler
};

using Handler = std::function<void(const RequestContext&, Respond)>;

class Router {
public:
    // `token`: when not empty, routes added with needsToken require "Authorization: Bearer <token>".
    explicit Router(std::string token = {}) : token_(std::move(token)) {}

    void add(std::string method, std::string pattern, Handler handler, bool needsToken = false);
    // For GET and HEAD requests no route matches (the web viewer's files).
    void setFallback(Handler handler) { fallback_ = std::move(handler); }

    // Answers through `respond` exactly once (400 for a malformed target, 404, 405 with Allow,
    // 401/403 for a missing or wrong token). Returns the route for metrics: "GET <pattern>",
    // "static" for the fallback, "unmatched" when nothing matched.
    std::string dispatch(const Request& request, Respond respond) const;

private:
    struct Route {
        std::string method;
        std::string pattern;
        std::vector<std::string> segments;
        Handler handler;
        bool needsToken = false;
    };
    bool authorised(const Request& request, Respond& respond) const;

    std::string token_;
    std::vector<Route> routes_;
    Handler fallback_;
};

} // namespace hexlod::server
