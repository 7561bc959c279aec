#include "hexlod/server/http_target.h"

#include <charconv>

namespace hexlod::server {
namespace {

int hexValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

bool forbidden(unsigned char c) {
    return c < 0x20 || c == 0x7f || c == '\\';
}

template <typename T> std::optional<T> parseWhole(std::string_view text) {
    if (text.empty() || text.size() > 20) return std::nullopt;
    if (text[0] == '+') return std::nullopt;
    T value{};
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return value;
}

} // namespace

std::optional<std::string_view> ParsedTarget::queryValue(std::string_view name) const {
    for (const auto& [key, value] : query)
        if (key == name) return value;
    return std::nullopt;
}

bool percentDecode(std::string_view in, std::string& out) {
    out.clear();
    out.reserve(in.size());
    for (size_t i = 0; i < in.size(); ++i) {
        if (in[i] != '%') {
            out.push_back(in[i]);
            continue;
        }
        if (i + 2 >= in.size()) return false;
        const int hi = hexValue(in[i + 1]), lo = hexValue(in[i + 2]);
        if (hi < 0 || lo < 0) return false;
        out.push_back(static_cast<char>(hi * 16 + lo));
        i += 2;
    }
    return true;
}

bool parseTarget(std::string_view target, ParsedTarget& out, std::string& error) {
    if (target.empty() || target[0] != '/')
        return error = "request target must be an absolute path (origin form), got '" +
                       std::string(target.substr(0, 64)) + "'",
               false;
    if (target.size() > kMaxTargetBytes)
        return error = "request target longer than " + std::to_string(kMaxTargetBytes) + " bytes", false;
    for (const char c : target)
        if (forbidden(static_cast<unsigned char>(c)) || c == ' ')
            return error = "request target holds a control byte, space or backslash", false;
    const size_t question = target.find('?');
    const std::string_view path = target.substr(0, question);
    if (path.find('#') != std::string_view::npos) return error = "request target holds a fragment", false;
    out.path = std::string(path);
    out.segments.clear();
    out.query.clear();
    size_t start = 1;
    while (true) {
        const size_t slash = path.find('/', start);
        const std::string_view raw =
            path.substr(start, slash == std::string_view::npos ? path.npos : slash - start);
        std::string decoded;
        if (!percentDecode(raw, decoded)) return error = "malformed percent escape in the path", false;
        for (const char c : decoded)
            if (forbidden(static_cast<unsigned char>(c)) || c == '/')
                return error = "path segment decodes to a control byte, slash or backslash", false;
        out.segments.push_back(std::move(decoded));
        if (slash == std::string_view::npos) break;
        start = slash + 1;
    }
    if (question == std::string_view::npos) return true;
    std::string_view query = target.substr(question + 1);
    while (!query.empty()) {
        const size_t amp = query.find('&');
        const std::string_view pair = query.substr(0, amp);
        const size_t eq = pair.find('=');
        std::string name, value;
        if (!percentDecode(pair.substr(0, eq), name) ||
            !percentDecode(eq == std::string_view::npos ? std::string_view() : pair.substr(eq + 1), value))
            return error = "malformed percent escape in the query", false;
        if (!name.empty()) out.query.emplace_back(std::move(name), std::move(value));
        if (amp == std::string_view::npos) break;
        query = query.substr(amp + 1);
    }
    return true;
}

std::optional<int32_t> parseInt32(std::string_view text) {
    return parseWhole<int32_t>(text);
}
std::optional<uint32_t> parseUint32(std::string_view text) {
    if (!text.empty() && text[0] == '-') return std::nullopt;
    return parseWhole<uint32_t>(text);
}
std::optional<uint64_t> parseUint64(std::string_view text) {
    if (!text.empty() && text[0] == '-') return std::nullopt;
    return parseWhole<uint64_t>(text);
}

std::optional<uint64_t> parseHexDigest(std::string_view text) {
    if (text.size() != 16) return std::nullopt;
    uint64_t value = 0;
    for (const char c : text) {
        const int v = hexValue(c);
        if (v < 0) return std::nullopt;
        value = value << 4 | uint64_t(v);
    }
    return value;
}

} // namespace hexlod::server
