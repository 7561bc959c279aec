#include "hexlod/server/service_api.h"

#include <nlohmann/json.hpp>

namespace hexlod::server {
namespace {

using Json = nlohmann::json;

// "3,-2" with two 32-bit whole numbers.
std::optional<cells::HexCoord> parseCell(std::string_view text) {
    const size_t comma = text.find(',');
    if (comma == std::string_view::npos) return std::nullopt;
    const auto q = parseInt32(text.substr(0, comma)), r = parseInt32(text.substr(comma + 1));
    if (!q || !r) return std::nullopt;
    return cells::HexCoord{*q, *r};
}

bool isJsonContentType(std::optional<std::string_view> value) {
    if (!value) return false;
    std::string type(value->substr(0, value->find(';')));
    while (!type.empty() && type.back() == ' ') type.pop_back();
    for (char& c : type) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return type == "application/json";
}

Reply outcomeReply(const EditOutcome& outcome) {
    Reply reply = jsonReply(outcome.status, jsonText(outcome.body) + "\n");
    reply.set("Cache-Control", "no-store");
    return reply;
}

// Runs an edit job on the edit thread; an exception becomes a 500 instead of ending the thread.
template <typename Job> void answerEdit(const Respond& respond, Job job) {
    try {
        respond(outcomeReply(job()));
    } catch (const std::exception& e) {
        respond(errorReply(500, std::string("internal error: ") + e.what()));
    }
}

std::string_view trimmed(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\n' || s.front() == '\r' || s.front() == '\t'))
        s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\n' || s.back() == '\r' || s.back() == '\t'))
        s.remove_suffix(1);
    return s;
}

} // namespace

Reply conditionalJson(const Request& request, const std::string& etag, std::string json) {
    Reply reply;
    if (!revalidated(request, etag, reply)) reply.body = std::move(json);
    return reply;
}

ServiceApi::ServiceApi(SceneService& service, ApiOptions options)
    : service_(service), options_(std::move(options)), router_(options_.token), static_(options_.webRoot) {
    Router& r = router_;
    r.add("GET", "/api/v1/scene", [this](const RequestContext& c, Respond respond) {
        respond(conditionalJson(c.request, service_.stateEtag(), jsonText(service_.summary()) + "\n"));
    });
    r.add("GET", "/api/v1/cells", [this](const RequestContext& c, Respond respond) {
        const SceneService::IndexView index = service_.cellIndex();
        respond(conditionalJson(c.request, index.etag, *index.json));
    });
    r.add("GET", "/api/v1/terminal-sets/{cell}/{grammar}/{key}",
          [this](const RequestContext& c, Respond respond) {
              content(PayloadKind::TerminalSet, c, std::move(respond));
          });
    r.add("GET", "/api/v1/extruded-sets/{cell}/{grammar}/{key}",
          [this](const RequestContext& c, Respond respond) {
              content(PayloadKind::ExtrudedSet, c, std::move(respond));
          });
    r.add("GET", "/api/v1/buildings/{id}", [this](const RequestContext& c, Respond respond) {
        const auto id = parseUint32(c.params[0]);
        if (!id)
            return respond(errorReply(400, "building id must be a whole number, got '" +
                                               std::string(c.params[0]) + "'"));
        const auto building = service_.building(*id);
        if (!building)
            return respond(errorReply(404, "building " + std::to_string(*id) + " is not in the scene"));
        respond(conditionalJson(c.request, service_.stateEtag(), jsonText(*building) + "\n"));
    });
    r.add("GET", "/api/v1/edits", [this](const RequestContext& c, Respond respond) {
        uint64_t since = 0;
        uint64_t limit = 1000;
        if (const auto v = c.target.queryValue("since")) {
            const auto n = parseUint64(*v);
            if (!n) return respond(errorReply(400, "since must be a whole number", "since"));
            since = *n;
        }
        if (const auto v = c.target.queryValue("limit")) {
            const auto n = parseUint64(*v);
            if (!n || *n == 0 || *n > 100000)
                return respond(errorReply(400, "limit must be in [1, 100000]", "limit"));
            limit = *n;
        }
        respond(conditionalJson(c.request, service_.stateEtag(),
                                jsonText(service_.history(since, static_cast<size_t>(limit))) + "\n"));
    });
    r.add(
        "POST", "/api/v1/edits",
        [this](const RequestContext& c, Respond respond) { postEdit(c, std::move(respond)); }, true);
    r.add(
        "POST", "/api/v1/edits/undo",
        [this](const RequestContext& c, Respond respond) { postUndo(c, std::move(respond)); }, true);
    r.add("GET", "/api/v1/events",
          [this](const RequestContext& c, Respond respond) { events(c, std::move(respond)); });
    r.add("GET", "/metrics", [this](const RequestContext&, Respond respond) {
        PrometheusText text;
        service_.renderMetrics(text);
        Reply reply;
        reply.contentType = "text/plain; version=0.0.4; charset=utf-8";
        reply.set("Cache-Control", "no-store");
        reply.body = text.take();
        respond(std::move(reply));
    });
    r.add("GET", "/healthz", [this](const RequestContext&, Respond respond) {
        Reply reply = jsonReply(200, jsonText(Json{{"status", "ok"}, {"seq", service_.lastSeq()}}) + "\n");
        reply.set("Cache-Control", "no-store");
        respond(std::move(reply));
    });
    r.add("GET", "/api/v1/meshes/{grammar}/{shape}/{file}",
          [this](const RequestContext& c, Respond respond) { shapeMesh(c, std::move(respond)); });
    r.add("GET", "/api/v1/impostors/{grammar}/{shape}/{file}",
          [this](const RequestContext& c, Respond respond) { shapeImpostor(c, std::move(respond)); });
    r.add("GET", "/api/v1/tree-impostors/{species}/{file}",
          [this](const RequestContext& c, Respond respond) { speciesImpostor(c, std::move(respond)); });
    r.setFallback(
        [this](const RequestContext& c, Respond respond) { respond(static_.serve(c.target, c.request)); });
}

void ServiceApi::content(PayloadKind kind, const RequestContext& c, Respond respond) const {
    const auto cell = parseCell(c.params[0]);
    if (!cell)
        return respond(errorReply(400, "cell must be 'q,r' with two 32-bit whole numbers, got '" +
                                           std::string(c.params[0]) + "'"));
    const auto grammarIndex = parseUint32(c.params[1]);
    if (!grammarIndex)
        return respond(errorReply(400, "grammar must be a grammar index (a whole number), got '" +
                                           std::string(c.params[1]) + "'"));
    const auto digest = parseHexDigest(c.params[2]);
    if (!digest)
        return respond(errorReply(400, "key must be 16 hex digits, got '" + std::string(c.params[2]) + "'"));
    const auto batch = service_.findBatch(*cell, *grammarIndex);
    if (!batch)
        return respond(errorReply(404, "no batch of grammar " + std::to_string(*grammarIndex) + " in cell (" +
                                           std::to_string(cell->q) + ", " + std::to_string(cell->r) + ")"));
    const BatchState state = service_.batchState(*batch);
    const std::string url = service_.contentUrl(kind, *batch, state.key);
    if (state.key.digest() != *digest) {
        Reply reply = errorReply(404, "key " + std::string(c.params[2]) +
                                          " is not this batch's current key; its content is now at " + url);
        reply.set("X-Hexlod-Current", url);
        return respond(std::move(reply));
    }
    const std::string etag = "\"" + state.key.hex() + "\"";
    const auto immutable = [etag, version = state.version](Reply& reply) {
        reply.set("ETag", etag);
        reply.set("Cache-Control", kImmutable);
        reply.set("X-Hexlod-Version", std::to_string(version));
    };
    if (const auto inm = c.request.header("if-none-match"); inm && etagMatches(*inm, etag)) {
        Reply reply;
        reply.status = 304;
        reply.contentType.clear();
        immutable(reply);
        return respond(std::move(reply));
    }
    const char* contentType =
        kind == PayloadKind::TerminalSet ? kTerminalSetContentType : kExtrudedSetContentType;
    service_.fetch(kind, *batch, state.key, [respond, immutable, contentType](const PayloadOutcome& outcome) {
        if (outcome.status != 200) {
            Reply reply = errorReply(outcome.status, outcome.error);
            if (outcome.status == 503) reply.set("Retry-After", "1");
            if (!outcome.current.empty()) reply.set("X-Hexlod-Current", outcome.current);
            return respond(std::move(reply));
        }
        Reply reply;
        reply.contentType = contentType;
        reply.payload = outcome.bytes;
        immutable(reply);
        respond(std::move(reply));
    });
}

void ServiceApi::postEdit(const RequestContext& c, Respond respond) const {
    if (!isJsonContentType(c.request.header("content-type")))
        return respond(errorReply(415, "an edit is a JSON body: send 'Content-Type: application/json'"));
    auto spec = std::make_shared<EditSpec>();
    EditError error;
    if (!parseEditBody(c.request.body, *spec, error))
        return respond(errorReply(400, error.text(), error.field));
    options_.runEdit(
        [this, spec, respond = std::move(respond)] { respond(outcomeReply(service_.edit(*spec))); });
}

void ServiceApi::postUndo(const RequestContext& c, Respond respond) const {
    const std::string_view body = trimmed(c.request.body);
    if (!body.empty() && body != "{}")
        return respond(errorReply(400, "an undo takes no parameters: send an empty body or {}"));
    options_.runEdit(
        [this, respond = std::move(respond)] { answerEdit(respond, [&] { return service_.undo(); }); });
}

void ServiceApi::events(const RequestContext& c, Respond respond) const {
    Reply reply;
    reply.eventStream = true;
    reply.contentType = "text/event-stream";
    if (const auto last = c.request.header("last-event-id")) {
        const auto id = parseUint64(*last);
        if (!id) return respond(errorReply(400, "Last-Event-ID must be a whole number (an edit seq)"));
        reply.lastEventId = *id;
    }
    respond(std::move(reply));
}

} // namespace hexlod::server
