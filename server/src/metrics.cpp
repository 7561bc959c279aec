#include "hexlod/server/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace hexlod::server {
namespace {

std::string formatValue(double v) {
    if (std::isinf(v)) return v > 0 ? "+Inf" : "-Inf";
    if (v == std::floor(v) && std::fabs(v) < 1e15) return std::to_string(static_cast<int64_t>(v));
    char text[32];
    std::snprintf(text, sizeof(text), "%.9g", v);
    return text;
}

std::string escapeLabel(const std::string& value) {
    std::string out;
    for (const char c : value) {
        if (c == '\\' || c == '"') out.push_back('\\');
        if (c == '\n') {
            out += "\\n";
            continue;
        }
        out.push_back(c);
    }
    return out;
}

std::string labelText(const PrometheusText::Labels& labels) {
    if (labels.empty()) return "";
    std::string out = "{";
    for (size_t i = 0; i < labels.size(); ++i) {
        if (i) out += ",";
        out += labels[i].first + "=\"" + escapeLabel(labels[i].second) + "\"";
    }
    return out + "}";
}

} // namespace

void Histogram::observe(double seconds) {
    size_t bucket = 0;
    while (bucket < kBounds.size() && seconds > kBounds[bucket]) ++bucket;
    counts_[bucket].fetch_add(1, std::memory_order_relaxed);
    sumNanos_.fetch_add(static_cast<uint64_t>(std::max(0.0, seconds) * 1e9), std::memory_order_relaxed);
}

Histogram::Snapshot Histogram::snapshot() const {
    Snapshot s;
    for (size_t i = 0; i < counts_.size(); ++i) {
        s.counts[i] = counts_[i].load(std::memory_order_relaxed);
        s.count += s.counts[i];
    }
    s.sum = static_cast<double>(sumNanos_.load(std::memory_order_relaxed)) * 1e-9;
    return s;
}

void PrometheusText::family(const std::string& name, const std::string& type, const std::string& help) {
    text_ += "# HELP " + name + " " + help + "\n# TYPE " + name + " " + type + "\n";
}

void PrometheusText::sample(const std::string& name, const Labels& labels, double value) {
    text_ += name + labelText(labels) + " " + formatValue(value) + "\n";
}

void PrometheusText::histogram(const std::string& name, const Labels& labels, const Histogram::Snapshot& h) {
    uint64_t cumulative = 0;
    for (size_t i = 0; i < h.counts.size(); ++i) {
        cumulative += h.counts[i];
        Labels with = labels;
        with.emplace_back("le", i < Histogram::kBounds.size() ? formatValue(Histogram::kBounds[i]) : "+Inf");
        sample(name + "_bucket", with, static_cast<double>(cumulative));
    }
    sample(name + "_sum", labels, h.sum);
    sample(name + "_count", labels, static_cast<double>(h.count));
}

void Metrics::recordRequest(const std::string& route, int status, double seconds, uint64_t bytesSent) {
    bytesSent_.fetch_add(bytesSent, std::memory_order_relaxed);
    std::lock_guard lock(mutex_);
    ++requests_[{route, status}];
    latency_[route].observe(seconds);
}

void Metrics::recordGeneration(const std::string& kind, double seconds) {
    std::lock_guard lock(mutex_);
    ++generations_[kind];
    generationSeconds_[kind].observe(seconds);
}

void Metrics::recordEdit(const std::string& op, const std::string& result) {
    std::lock_guard lock(mutex_);
    ++edits_[{op, result}];
}

void Metrics::render(PrometheusText& out) const {
    std::lock_guard lock(mutex_);
    out.family("hexlod_http_requests_total", "counter",
               "HTTP requests answered, by route pattern and status.");
    for (const auto& [key, count] : requests_)
        out.sample("hexlod_http_requests_total",
                   {{"route", key.first}, {"status", std::to_string(key.second)}},
                   static_cast<double>(count));
    out.family("hexlod_http_request_duration_seconds", "histogram",
               "Time from a complete request to its reply being written, by route pattern.");
    for (const auto& [route, h] : latency_)
        out.histogram("hexlod_http_request_duration_seconds", {{"route", route}}, h.snapshot());
    out.family("hexlod_http_response_bytes_total", "counter", "Body bytes sent, event streams excluded.");
    out.sample("hexlod_http_response_bytes_total", {}, static_cast<double>(bytesSent_.load()));
    out.family("hexlod_http_connections_opened_total", "counter", "TCP connections accepted.");
    out.sample("hexlod_http_connections_opened_total", {}, static_cast<double>(connectionsOpened.load()));
    out.family("hexlod_http_connections_open", "gauge", "TCP connections open now, event streams included.");
    out.sample("hexlod_http_connections_open", {}, static_cast<double>(connectionsOpen.load()));
    out.family("hexlod_http_connections_refused_total", "counter",
               "Connections turned away at the connection limit.");
    out.sample("hexlod_http_connections_refused_total", {}, static_cast<double>(connectionsRefused.load()));
    out.family("hexlod_http_rate_limited_total", "counter",
               "Requests answered 429 by the per-client rate limit.");
    out.sample("hexlod_http_rate_limited_total", {}, static_cast<double>(rateLimited.load()));
    out.family("hexlod_http_malformed_total", "counter", "Requests the HTTP parser rejected.");
    out.sample("hexlod_http_malformed_total", {}, static_cast<double>(malformed.load()));
    out.family("hexlod_generations_total", "counter",
               "Batch expansions run for content requests, by what asked.");
    for (const auto& [kind, count] : generations_)
        out.sample("hexlod_generations_total", {{"kind", kind}}, static_cast<double>(count));
    out.family("hexlod_generation_seconds", "histogram", "Expansion plus encoding time per generated batch.");
    for (const auto& [kind, h] : generationSeconds_)
        out.histogram("hexlod_generation_seconds", {{"kind", kind}}, h.snapshot());
    out.family("hexlod_edits_total", "counter", "Edit and undo requests by outcome.");
    for (const auto& [key, count] : edits_)
        out.sample("hexlod_edits_total", {{"op", key.first}, {"result", key.second}},
                   static_cast<double>(count));
    out.family("hexlod_journal_sync_seconds", "histogram", "Journal append plus fdatasync time per entry.");
    out.histogram("hexlod_journal_sync_seconds", {}, journalSync_.snapshot());
}

} // namespace hexlod::server
