#include "expansion_report.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

namespace hexlod::apps {
namespace {

// Full facade geometry the terminals stand for: each triangle as three unindexed vertices
// of position, normal and texture coordinate (3 + 3 + 2 floats = 32 bytes).
constexpr uint64_t kBytesPerGeometryTriangle = 3 * 32;

} // namespace

Timing timeExpansion(const grammar::BatchInput& input, uint32_t repeat) {
    std::vector<double> seconds;
    Timing timing;
    for (uint32_t i = 0; i < std::max(1u, repeat); ++i) {
        const auto start = std::chrono::steady_clock::now();
        grammar::BatchResult result = grammar::expandBatch(input);
        seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        if (i == 0) {
            timing.coldSeconds = seconds.back();
            timing.result = std::move(result);
        }
    }
    std::sort(seconds.begin(), seconds.end());
    const size_t n = seconds.size();
    timing.medianSeconds = n % 2 ? seconds[n / 2] : 0.5 * (seconds[n / 2 - 1] + seconds[n / 2]);
    return timing;
}

nlohmann::json batchStats(const grammar::CompiledGrammar& g, const std::string& name, size_t buildings,
                          uint32_t threads, uint32_t repeat, const Timing& timing) {
    const grammar::BatchResult& r = timing.result;
    const uint64_t terminals = r.terminals.records.size();
    uint64_t geometryBytes = 0;
    nlohmann::json perShape = nlohmann::json::object();
    for (size_t s = 0; s < g.shapes.size(); ++s) {
        geometryBytes +=
            uint64_t(r.terminals.countPerShape[s]) * g.shapes[s].triangles * kBytesPerGeometryTriangle;
        if (r.terminals.countPerShape[s] > 0) perShape[g.shapes[s].name] = r.terminals.countPerShape[s];
    }
    const uint64_t bytes = r.terminals.byteSize();
    nlohmann::json issues = nlohmann::json::array();
    for (const grammar::BatchIssue& issue : r.issues)
        issues.push_back(describeIssue(g, issue.first, issue.occurrences));
    return {
        {"grammar", name},
        {"buildings", buildings},
        {"buildings_expanded", r.buildingsExpanded},
        {"buildings_skipped", r.buildingsSkipped},
        {"atoms", r.atoms},
        {"terminals", terminals},
        {"terminals_per_shape", perShape},
        {"bytes", bytes},
        {"bytes_per_terminal", terminals ? double(bytes) / double(terminals) : 0.0},
        {"record_bytes", sizeof(grammar::TerminalRecord)},
        {"extruded_bytes", r.extruded.byteSize()},
        {"geometry_bytes", geometryBytes},
        {"geometry_to_terminal_ratio", bytes ? double(geometryBytes) / double(bytes) : 0.0},
        {"seconds", timing.medianSeconds},
        {"cold_seconds", timing.coldSeconds},
        {"repeat", std::max(1u, repeat)},
        {"terminals_per_second", timing.medianSeconds > 0 ? double(terminals) / timing.medianSeconds : 0.0},
        {"threads", threads},
        {"failed", r.failed},
        {"issues", issues},
    };
}

void printBatchStats(const nlohmann::json& stats) {
    std::printf("grammar      %s\n", stats["grammar"].get<std::string>().c_str());
    std::printf("buildings    %zu (%u skipped), atoms %llu\n", stats["buildings"].get<size_t>(),
                stats["buildings_skipped"].get<unsigned>(), stats["atoms"].get<unsigned long long>());
    std::printf("terminals    %llu\n", stats["terminals"].get<unsigned long long>());
    for (const auto& [name, count] : stats["terminals_per_shape"].items()) {
        std::printf("  %-22s %llu\n", name.c_str(), count.get<unsigned long long>());
    }
    std::printf("bytes        %llu (%.2f B/terminal), extruded set %llu\n",
                stats["bytes"].get<unsigned long long>(), stats["bytes_per_terminal"].get<double>(),
                stats["extruded_bytes"].get<unsigned long long>());
    std::printf("geometry     %llu bytes (%.0fx the terminal set)\n",
                stats["geometry_bytes"].get<unsigned long long>(),
                stats["geometry_to_terminal_ratio"].get<double>());
    std::printf("time         %.4f s median of %u on %u threads (%.2f M terminals/s)\n",
                stats["seconds"].get<double>(), stats["repeat"].get<unsigned>(),
                stats["threads"].get<unsigned>(), stats["terminals_per_second"].get<double>() / 1e6);
}

bool reportIssues(const grammar::CompiledGrammar& g, const grammar::BatchResult& result) {
    bool errors = result.failed;
    for (const grammar::BatchIssue& issue : result.issues) {
        std::cerr << describeIssue(g, issue.first, issue.occurrences) << "\n";
        errors = errors || grammar::issueIsError(issue.first.kind);
    }
    return errors;
}

} // namespace hexlod::apps
