// Service metrics in the Prometheus text exposition format, version 0.0.4
// (https://prometheus.io/docs/instrumenting/exposition_formats/): counters, gauges and
// cumulative histograms, rendered on GET /metrics. Labels stay low-cardinality: requests
// are counted by route pattern, never by raw path.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace hexlod::server {

// Fixed buckets, upper bounds in seconds; the +Inf bucket is implicit.
class Histogram {
public:
    static constexpr std::array<double, 15> kBounds = {
        0.0001, 0.00025, 0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1.0, 2.5, 10.0};
    void observe(double seconds);
    struct Snapshot {
        std::array<uint64_t, kBounds.size() + 1> counts{}; // per bucket, not cumulative
        double sum = 0.0;
        uint64_t count = 0;
    };
    Snapshot snapshot() const;

private:
    std::array<std::atomic<uint64_t>, kBounds.size() + 1> counts_{};
    std::atomic<uint64_t> sumNanos_{0};
};

// Builds the exposition text family by family.
class PrometheusText {
public:
    using Labels = std::vector<std::pair<std::string, std::string>>;
    void family(const std::string& name, const std::string& type, const std::string& help);
    void sample(const std::string& name, const Labels& labels, double value);
    void histogram(const std::string& name, const Labels& labels, const Histogram::Snapshot& h);
    std::string take() { return std::move(text_); }

private:
    std::string text_;
};

class Metrics {
public:
    void recordRequest(const std::string& route, int status, double seconds, uint64_t bytesSent);
    void recordGeneration(const std::string& kind, double seconds);
    void recordEdit(const std::string& op, const std::string& result);
    void recordJournalSync(double seconds) { journalSync_.observe(seconds); }

    std::atomic<uint64_t> connectionsOpened{0};
    std::atomic<int64_t> connectionsOpen{0};
    std::atomic<uint64_t> connectionsRefused{0}; // over the connection limit
    std::atomic<uint64_t> rateLimited{0};
    std::atomic<uint64_t> malformed{0}; // requests the parser rejected

    // Appends the request, generation, edit and connection families.
    void render(PrometheusText& out) const;

private:
    mutable std::mutex mutex_;
    std::map<std::pair<std::string, int>, uint64_t> requests_;
    std::map<std::string, Histogram> latency_; // node-based: histograms never move
    std::map<std::string, uint64_t> generations_;
    std::map<std::string, Histogram> generationSeconds_;
    std::map<std::pair<std::string, std::string>, uint64_t> edits_;
    std::atomic<uint64_t> bytesSent_{0};
    Histogram journalSync_;
};

} // namespace hexlod::server
