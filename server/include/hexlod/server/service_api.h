// The HTTP API of docs/protocol.md: every route of /api/v1, /metrics, /healthz and the web
// viewer's files, on a Router over a SceneService. Beast-free: the HTTP session feeds it
// Requests and writes its Replies, and the fuzz target calls it directly.
#pragma once

#include "hexlod/server/router.h"
#include "hexlod/server/scene_service.h"
#include "hexlod/server/static_files.h"

#include <functional>
#include <string>

namespace hexlod::server {

inline constexpr const char* kTerminalSetContentType = "application/vnd.hexlod.terminal-set";
inline constexpr const char* kExtrudedSetContentType = "application/vnd.hexlod.extruded-set";
inline constexpr const char* kImmutable = "public, max-age=31536000, immutable";

struct ApiOptions {
    std::string token;   // edits need "Authorization: Bearer <token>" when set
    std::string webRoot; // the web viewer's folder
    // Runs edit work off the I/O threads, one job at a time (journal order is edit order).
    std::function<void(std::function<void()>)> runEdit;
};

class ServiceApi {
public:
    ServiceApi(SceneService& service, ApiOptions options);

    // Answers through `respond` exactly once; returns the route pattern for metrics.
    std::string handle(const Request& request, Respond respond) const {
        return router_.dispatch(request, std::move(respond));
    }
    Router& router() { return router_; }
    const StaticFiles& staticFiles() const { return static_; }

private:
    void content(PayloadKind kind, const RequestContext& context, Respond respond) const;
    void shapeMesh(const RequestContext& context, Respond respond) const;       // shape_asset_routes.cpp
    void shapeImpostor(const RequestContext& context, Respond respond) const;   // shape_asset_routes.cpp
    void speciesImpostor(const RequestContext& context, Respond respond) const; // shape_asset_routes.cpp
    void postEdit(const RequestContext& context, Respond respond) const;
    void postUndo(const RequestContext& context, Respond respond) const;
    void events(const RequestContext& context, Respond respond) const;

    SceneService& service_;
    ApiOptions options_;
    Router router_;
    StaticFiles static_;
};

// A JSON reply with a weak ETag and Cache-Control: no-cache, or 304 when If-None-Match matches.
Reply conditionalJson(const Request& request, const std::string& etag, std::string json);

} // namespace hexlod::server
