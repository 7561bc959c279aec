#include "expand_command.h"

#include "terminal_set_file.h"

#include "hexlod/grammar/batch_expander.h"
#include "hexlod/scene/demo_footprints.h"
#include "hexlod/scene/geojson_footprints.h"

#include <nlohmann/json.hpp>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace hexlod::apps {
namespace {

using grammar::BatchResult;
using grammar::CompiledGrammar;

// Full facade geometry the terminals stand for: each triangle as three unindexed vertices
// of position, normal and texture coordinate (3 + 3 + 2 floats = 32 bytes).
constexpr uint64_t kBytesPerGeometryTriangle = 3 * 32;

bool parseParam(const std::string& text, grammar::ParameterOverride& out, std::string& error) {
    const size_t equals = text.find('=');
    if (equals == std::string::npos || equals == 0) {
        error = "--param expects name=value, got '" + text + "'";
        return false;
    }
    out.name = text.substr(0, equals);
    const std::string value = text.substr(equals + 1);
    char* end = nullptr;
    out.value = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0') {
        error = "--param " + out.name + ": '" + value + "' is not a number";
        return false;
    }
    return true;
}

struct Timing {
    double medianSeconds = 0.0;
    double coldSeconds = 0.0; // the first run, before any memory is recycled
    BatchResult result;
};

Timing timeExpansion(const grammar::BatchInput& input, uint32_t repeat) {
    std::vector<double> seconds;
    Timing timing;
    for (uint32_t i = 0; i < std::max(1u, repeat); ++i) {
        const auto start = std::chrono::steady_clock::now();
        BatchResult result = grammar::expandBatch(input);
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

nlohmann::json statsJson(const CompiledGrammar& g, const ExpandOptions& options, size_t buildings,
                         uint32_t threads, const Timing& timing) {
    const BatchResult& r = timing.result;
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
        {"grammar", options.grammarPath},
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
        {"repeat", std::max(1u, options.repeat)},
        {"terminals_per_second", timing.medianSeconds > 0 ? double(terminals) / timing.medianSeconds : 0.0},
        {"threads", threads},
        {"failed", r.failed},
        {"issues", issues},
    };
}

void printStats(const nlohmann::json& stats) {
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

// Imported footprints with a known height get `floors = height / floor_h` when the grammar
// has both parameters; the rest vary by seed like the demo city.
std::vector<grammar::ParameterOverride> heightOverrides(const CompiledGrammar& g, double height) {
    const int floors = g.findParameter("floors"), floorHeight = g.findParameter("floor_h");
    if (floors < 0 || floorHeight < 0 || !std::isfinite(height)) return {};
    const grammar::ParameterInfo& info = g.params[floors];
    const double count = std::round(height / g.params[floorHeight].defaultValue);
    return {{"floors", std::clamp(count, double(info.minValue), double(info.maxValue))}};
}

bool loadBuildings(const ExpandOptions& options, const CompiledGrammar& g,
                   const std::vector<grammar::ParameterOverride>& overrides,
                   std::vector<grammar::BuildingInput>& buildings) {
    std::vector<double> heights;
    if (!options.footprintsPath.empty()) {
        scene::ImportedFootprints imported;
        std::string error;
        if (!scene::readGeoJsonFootprints(options.footprintsPath, imported, error)) {
            std::cerr << "hexlod expand: " << error << "\n";
            return false;
        }
        std::cerr << "imported " << imported.buildings.size() << " footprints from " << imported.features
                  << " features of " << options.footprintsPath << "\n";
        for (const auto& [reason, count] : imported.skipped) {
            std::cerr << "  skipped " << count << " features: " << reason << "\n";
        }
        if (imported.holesIgnored > 0) {
            std::cerr << "  ignored " << imported.holesIgnored
                      << " inner rings (footprints use outer rings)\n";
        }
        buildings = std::move(imported.buildings);
        heights = std::move(imported.heights);
    } else {
        buildings = scene::makeDemoFootprints({options.demoCount, options.seed, 60.0});
    }
    for (size_t i = 0; i < buildings.size(); ++i) {
        grammar::BuildingInput& b = buildings[i];
        std::vector<grammar::ParameterOverride> mine =
            i < heights.size() && std::isfinite(heights[i])
                ? heightOverrides(g, heights[i])
                : scene::demoParameterOverrides(g, options.seed, b.id);
        mine.insert(mine.end(), overrides.begin(), overrides.end()); // explicit --param wins
        grammar::DiagnosticList ignored;
        b.parameters = grammar::resolveParameters(g, mine, ignored);
    }
    return true;
}

} // namespace

CLI::App* registerExpandCommand(CLI::App& app, ExpandOptions& o) {
    CLI::App* cmd = app.add_subcommand("expand", "Expand a grammar over footprints into a terminal set");
    cmd->add_option("--grammar", o.grammarPath, "Grammar file (.grammar)")
        ->required()
        ->check(CLI::ExistingFile);
    auto* footprints = cmd->add_option("--footprints", o.footprintsPath,
                                       "GeoJSON footprints (Polygon, MultiPolygon in lon/lat)")
                           ->check(CLI::ExistingFile);
    auto* demo = cmd->add_option("--demo", o.demoCount, "Expand N procedural demo footprints")
                     ->check(CLI::Range(1u, 10000000u));
    footprints->excludes(demo);
    cmd->add_option("--param", o.params, "Override a parameter for every building: name=value");
    cmd->add_option("--threads", o.threads, "Worker threads (default: all)")->check(CLI::Range(1u, 1024u));
    cmd->add_option("--repeat", o.repeat, "Time the expansion N times and report the median")
        ->check(CLI::Range(1u, 1000u));
    cmd->add_option("--seed", o.seed, "Scene seed for footprints and stochastic rules");
    cmd->add_option("--out", o.outPath, "Write the terminal set to this file");
    cmd->add_flag("--stats", o.stats, "Print statistics");
    cmd->add_flag("--json", o.json, "Print statistics as one JSON object");
    return cmd;
}

int runExpandCommand(const ExpandOptions& options) {
    if (options.demoCount == 0 && options.footprintsPath.empty()) {
        std::cerr << "hexlod expand: give --demo N (or --footprints F.geojson)\n";
        return 2;
    }
    grammar::DiagnosticList diagnostics;
    const CompiledGrammar g = grammar::compileGrammarFile(options.grammarPath, diagnostics);
    std::cerr << diagnostics.formatAll();
    if (diagnostics.hasErrors()) return 1;

    std::vector<grammar::ParameterOverride> overrides;
    for (const std::string& text : options.params) {
        grammar::ParameterOverride o;
        std::string error;
        if (!parseParam(text, o, error)) {
            std::cerr << "hexlod expand: " << error << "\n";
            return 2;
        }
        overrides.push_back(o);
    }
    grammar::DiagnosticList paramErrors;
    grammar::resolveParameters(g, overrides, paramErrors);
    if (paramErrors.hasErrors()) {
        std::cerr << paramErrors.formatAll();
        return 2;
    }

    std::vector<grammar::BuildingInput> buildings;
    if (!loadBuildings(options, g, overrides, buildings)) return 1;

    const uint32_t threads =
        options.threads ? options.threads : static_cast<uint32_t>(tbb::info::default_concurrency());
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    grammar::BatchInput input;
    input.grammar = &g;
    input.buildings = buildings;
    input.settings.seed = options.seed;
    const Timing timing = timeExpansion(input, options.repeat);

    for (const grammar::BatchIssue& issue : timing.result.issues) {
        std::cerr << describeIssue(g, issue.first, issue.occurrences) << "\n";
    }
    if (!options.outPath.empty()) {
        std::string error;
        if (!writeTerminalSetFile(options.outPath, timing.result.terminals, error)) {
            std::cerr << "hexlod expand: " << error << "\n";
            return 1;
        }
    }
    const nlohmann::json stats = statsJson(g, options, buildings.size(), threads, timing);
    if (options.json) {
        std::cout << stats.dump(2) << "\n";
    } else if (options.stats || options.outPath.empty()) {
        printStats(stats);
    }
    bool errors = timing.result.failed;
    for (const grammar::BatchIssue& issue : timing.result.issues)
        errors = errors || grammar::issueIsError(issue.first.kind);
    return errors ? 1 : 0;
}

} // namespace hexlod::apps
