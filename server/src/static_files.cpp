#include "hexlod/server/static_files.h"

#include <filesystem>
#include <map>
#include <system_error>

namespace hexlod::server {
namespace {

namespace fs = std::filesystem;

std::string_view stripWeak(std::string_view tag) {
    if (tag.size() >= 2 && tag[0] == 'W' && tag[1] == '/') tag.remove_prefix(2);
    return tag;
}

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

bool isWithin(const fs::path& path, const std::string& root) {
    const std::string p = path.string();
    return p == root ||
           (p.size() > root.size() && p.compare(0, root.size(), root) == 0 && p[root.size()] == '/');
}

} // namespace

bool etagMatches(std::string_view ifNoneMatch, std::string_view etag) {
    if (trim(ifNoneMatch) == "*") return true;
    const std::string_view want = stripWeak(etag);
    while (!ifNoneMatch.empty()) {
        const size_t comma = ifNoneMatch.find(',');
        if (stripWeak(trim(ifNoneMatch.substr(0, comma))) == want) return true;
        if (comma == std::string_view::npos) break;
        ifNoneMatch.remove_prefix(comma + 1);
    }
    return false;
}

bool revalidated(const Request& request, const std::string& etag, Reply& reply) {
    reply.set("ETag", etag);
    reply.set("Cache-Control", "no-cache");
    const auto inm = request.header("if-none-match");
    if (!inm || !etagMatches(*inm, etag)) return false;
    reply.status = 304;
    reply.contentType.clear();
    return true;
}

StaticFiles::StaticFiles(std::string root) : root_(std::move(root)) {
    std::error_code ec;
    const fs::path canonical = fs::canonical(root_, ec);
    if (!ec && fs::is_directory(canonical, ec)) canonicalRoot_ = canonical.string();
}

std::string StaticFiles::contentTypeFor(const std::string& path) {
    static const std::map<std::string, std::string> types = {
        {".html", "text/html; charset=utf-8"},
        {".htm", "text/html; charset=utf-8"},
        {".js", "text/javascript; charset=utf-8"},
        {".mjs", "text/javascript; charset=utf-8"},
        {".css", "text/css; charset=utf-8"},
        {".json", "application/json"},
        {".map", "application/json"},
        {".txt", "text/plain; charset=utf-8"},
        {".svg", "image/svg+xml"},
        {".png", "image/png"},
        {".jpg", "image/jpeg"},
        {".jpeg", "image/jpeg"},
        {".gif", "image/gif"},
        {".webp", "image/webp"},
        {".ico", "image/x-icon"},
        {".wasm", "application/wasm"},
        {".glb", "model/gltf-binary"},
        {".gltf", "model/gltf+json"},
        {".bin", "application/octet-stream"},
        {".ktx2", "image/ktx2"},
        {".exr", "image/x-exr"},
        {".woff", "font/woff"},
        {".woff2", "font/woff2"},
    };
    std::string extension = fs::path(path).extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const auto it = types.find(extension);
    return it == types.end() ? "application/octet-stream" : it->second;
}

Reply StaticFiles::serve(const ParsedTarget& target, const Request& request) const {
    std::vector<std::string> parts;
    for (const std::string& segment : target.segments) {
        if (segment == "." || segment == "..")
            return errorReply(400, "path traversal ('.' or '..' segment) is not allowed");
        if (segment.empty()) continue;
        if (segment[0] == '.') return errorReply(404, "no such file (hidden names are not served)");
        parts.push_back(segment);
    }
    if (!available()) {
        if (parts.empty() || (parts.size() == 1 && parts[0] == "index.html")) return builtInPage();
        return errorReply(404, "the web viewer is not built (no folder '" + root_ + "'); see /");
    }
    fs::path path = canonicalRoot_;
    for (const std::string& part : parts) path /= part;
    std::error_code ec;
    fs::path resolved = fs::canonical(path, ec);
    if (!ec && fs::is_directory(resolved, ec)) resolved = fs::canonical(resolved / "index.html", ec);
    if (ec) return errorReply(404, "no such file: " + target.path);
    if (!isWithin(resolved, canonicalRoot_)) return errorReply(403, "the path leads outside the web root");
    const fs::file_status status = fs::status(resolved, ec);
    if (ec || !fs::is_regular_file(status)) return errorReply(404, "no such file: " + target.path);
    const uint64_t size = fs::file_size(resolved, ec);
    const auto modified = fs::last_write_time(resolved, ec).time_since_epoch().count();
    if (ec) return errorReply(404, "no such file: " + target.path);

    Reply reply;
    if (revalidated(request, "W/\"" + std::to_string(size) + "-" + std::to_string(modified) + "\"", reply))
        return reply;
    reply.contentType = contentTypeFor(resolved.string());
    reply.filePath = resolved.string();
    reply.fileBytes = size;
    return reply;
}

Reply StaticFiles::builtInPage() const {
    std::string root;
    for (const char c : root_)
        root += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
    Reply reply;
    reply.contentType = "text/html; charset=utf-8";
    reply.set("Cache-Control", "no-cache");
    reply.body = R"(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>hexlod</title>
<style>body{font:15px/1.5 system-ui,sans-serif;max-width:46em;margin:2em auto;padding:0 1em}code{background:#eee;padding:0 .2em}</style>
</head><body>
<h1>hexlod</h1>
<p>The service is running, but the web viewer is not built: there is no <code>)" +
                 root + R"(</code> folder. Build it (see <code>web/README.md</code>) or start the service with
<code>--web-root DIR</code>.</p>
<h2>API</h2>
<ul>
<li><a href="/api/v1/scene"><code>GET /api/v1/scene</code></a>: scene summary, grammars and their parameters, LOD profile, notes</li>
<li><a href="/api/v1/cells"><code>GET /api/v1/cells</code></a>: the cell index with every batch's content URLs</li>
<li><code>GET /api/v1/terminal-sets/{q},{r}/{grammar}/{key}</code>: a batch's terminal set (binary)</li>
<li><code>GET /api/v1/extruded-sets/{q},{r}/{grammar}/{key}</code>: a batch's extruded set (binary)</li>
<li><code>GET /api/v1/buildings/{id}</code>: one building's grammar, cell and parameters</li>
<li><code>POST /api/v1/edits</code>, <a href="/api/v1/edits"><code>GET /api/v1/edits</code></a>, <code>POST /api/v1/edits/undo</code>: parameter edits</li>
<li><code>GET /api/v1/events</code>: change events (Server-Sent Events)</li>
<li><a href="/metrics"><code>GET /metrics</code></a> and <a href="/healthz"><code>GET /healthz</code></a></li>
</ul>
<p>Formats and examples: <code>docs/protocol.md</code>.</p>
</body></html>
)";
    return reply;
}

} // namespace hexlod::server
