#include "expand_scene.h"

#include "expansion_report.h"

#include "hexlod/scene/scene_builder.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <cstdio>
#include <iostream>

namespace hexlod::apps {
namespace {

struct Totals {
    uint64_t buildings = 0, atoms = 0, terminals = 0, bytes = 0, geometryBytes = 0, extrudedBytes = 0;
    double seconds = 0.0;

    void add(const nlohmann::json& stats) {
        buildings += stats["buildings"].get<uint64_t>();
        atoms += stats["atoms"].get<uint64_t>();
        terminals += stats["terminals"].get<uint64_t>();
        bytes += stats["bytes"].get<uint64_t>();
        geometryBytes += stats["geometry_bytes"].get<uint64_t>();
        extrudedBytes += stats["extruded_bytes"].get<uint64_t>();
        seconds += stats["seconds"].get<double>();
    }
};

} // namespace

int runSceneExpansion(const ExpandOptions& options) {
    scene::SceneConfig config;
    std::string error;
    if (!scene::loadSceneConfig(options.scenePath, config, error)) {
        std::cerr << "hexlod expand: " << error << "\n";
        return 2;
    }
    scene::BuiltScene built;
    if (!scene::buildScene(config, built, error)) {
        std::cerr << "hexlod expand: " << error << "\n";
        return 1;
    }
    for (const std::string& note : built.notes) std::cerr << "scene " << config.name << ": " << note << "\n";
    for (const std::string& credit : built.attributions) std::cerr << "data: " << credit << "\n";

    const uint32_t threads =
        options.threads ? options.threads : static_cast<uint32_t>(tbb::info::default_concurrency());
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    nlohmann::json batches = nlohmann::json::array();
    Totals buildings, trees;
    bool errors = false;
    auto expandAll = [&](const std::vector<scene::GrammarBuildings>& list, Totals& totals) {
        for (const scene::GrammarBuildings& batch : list) {
            if (batch.buildings.empty()) continue; // an unused grammar costs nothing
            grammar::BatchInput input;
            input.grammar = &batch.grammar;
            input.buildings = batch.buildings;
            input.settings.seed = config.seed;
            const Timing timing = timeExpansion(input, options.repeat);
            errors = reportIssues(batch.grammar, timing.result) || errors;
            nlohmann::json stats = batchStats(batch.grammar, batch.name, batch.buildings.size(), threads,
                                              options.repeat, timing);
            totals.add(stats);
            if (!options.json) printBatchStats(stats);
            batches.push_back(std::move(stats));
        }
    };
    expandAll(built.buildingGrammars, buildings);
    expandAll(built.treeGrammars, trees);

    const uint64_t terminals = buildings.terminals + trees.terminals, bytes = buildings.bytes + trees.bytes;
    const double seconds = buildings.seconds + trees.seconds;
    const nlohmann::json summary = {
        {"scene", config.name},
        {"notes", built.notes},
        {"attributions", built.attributions},
        {"batches", batches},
        {"buildings", buildings.buildings},
        {"trees", trees.buildings},
        {"atoms", buildings.atoms + trees.atoms},
        {"terminals", terminals},
        {"building_terminals", buildings.terminals},
        {"tree_terminals", trees.terminals},
        {"bytes", bytes},
        {"bytes_per_terminal", terminals ? double(bytes) / double(terminals) : 0.0},
        {"extruded_bytes", buildings.extrudedBytes + trees.extrudedBytes},
        {"geometry_bytes", buildings.geometryBytes + trees.geometryBytes},
        {"seconds", seconds},
        {"terminals_per_second", seconds > 0 ? double(terminals) / seconds : 0.0},
        {"threads", threads},
    };
    if (options.json) {
        std::cout << summary.dump(2) << "\n";
    } else {
        std::printf("scene        %s: %llu buildings, %llu trees, %llu terminals (%.1f MB) for %.1f GB of "
                    "geometry, %.3f s (%.2f M terminals/s)\n",
                    config.name.c_str(), (unsigned long long)buildings.buildings,
                    (unsigned long long)trees.buildings, (unsigned long long)terminals, bytes / 1e6,
                    (buildings.geometryBytes + trees.geometryBytes) / 1e9, seconds,
                    seconds > 0 ? terminals / seconds / 1e6 : 0.0);
    }
    return errors ? 1 : 0;
}

} // namespace hexlod::apps
