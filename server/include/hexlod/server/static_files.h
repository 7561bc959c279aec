// The web viewer's files (web/dist by default) under "/". A path resolves inside the root or
// not at all: "." and ".." segments (also percent-encoded) are refused, hidden names are not
// served, and the resolved file's canonical path must lie under the canonical root, so a
// symbolic link cannot lead out of it. Without a built viewer, "/" is a small built-in page
// that says so and lists the API.
#pragma once

#include "hexlod/server/http_target.h"
#include "hexlod/server/http_types.h"

#include <string>

namespace hexlod::server {

class StaticFiles {
public:
    explicit StaticFiles(std::string root);

    bool available() const { return !canonicalRoot_.empty(); }
    const std::string& root() const { return root_; }
    // For GET and HEAD of a path outside /api and the service's own routes.
    Reply serve(const ParsedTarget& target, const Request& request) const;

    static std::string contentTypeFor(const std::string& path);

private:
    Reply builtInPage() const;

    std::string root_;
    std::string canonicalRoot_; // empty when the folder does not exist
};

// Gives `reply` its ETag and Cache-Control: no-cache, and turns it into a 304 when the
// request's If-None-Match matches; true then (the caller sends it without a body).
bool revalidated(const Request& request, const std::string& etag, Reply& reply);

// True when `ifNoneMatch` (an If-None-Match value: "*" or a list of entity tags) matches
// `etag` by the weak comparison of RFC 9110 §8.8.3.2.
bool etagMatches(std::string_view ifNoneMatch, std::string_view etag);

} // namespace hexlod::server
