// From a request Boost.Beast parsed to the service's Request, and the checks every request
// must pass before it is routed (HTTP version, Host). Shared by the HTTP session and the
// request fuzz target, so that both see the same rules.
#pragma once

#include "hexlod/server/http_types.h"

#include <boost/beast/http/message.hpp>
#include <boost/beast/http/string_body.hpp>

#include <optional>
#include <string>

namespace hexlod::server {

using BeastRequest = boost::beast::http::request<boost::beast::http::string_body>;

// The error reply for a request that is well-formed HTTP but not one this service takes:
// a version other than 1.0 or 1.1 (505), or no Host header (400). nullopt when it may be routed.
std::optional<Reply> rejectBeforeRouting(const BeastRequest& message);

// Header names lower-cased, the body moved out of `message`.
Request toRequest(BeastRequest&& message, std::string remoteAddress);

} // namespace hexlod::server
