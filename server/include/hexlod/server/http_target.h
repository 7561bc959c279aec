// Request-target parsing (RFC 9112 §3.2, origin form only): the path split into segments,
// the query into name/value pairs, percent-decoding that rejects what a path must never
// hold, and strict number parsing for path parameters such as "3,-2".
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hexlod::server {

inline constexpr size_t kMaxTargetBytes = 4096;

struct ParsedTarget {
    std::string path;                  // raw, before percent-decoding, always starting with '/'
    std::vector<std::string> segments; // decoded, split on '/'; empty segments kept
    std::vector<std::pair<std::string, std::string>> query; // decoded
    std::optional<std::string_view> queryValue(std::string_view name) const;
};

// Returns false with `error` for anything but an origin-form target ("/path?query") of at
// most kMaxTargetBytes, with valid percent escapes and no control bytes, NUL or backslash
// after decoding.
bool parseTarget(std::string_view target, ParsedTarget& out, std::string& error);

// Decodes %XX escapes; false on a malformed escape. '+' stays '+'.
bool percentDecode(std::string_view in, std::string& out);

// Whole decimal integers only: no sign for unsigned, no spaces, no leading '+', in range.
std::optional<int32_t> parseInt32(std::string_view text);
std::optional<uint32_t> parseUint32(std::string_view text);
std::optional<uint64_t> parseUint64(std::string_view text);
// Exactly 16 lowercase or uppercase hex digits.
std::optional<uint64_t> parseHexDigest(std::string_view text);

} // namespace hexlod::server
