#include "expand_command.h"

#include "expand_scene.h"
#include "expansion_report.h"
#include "terminal_set_file.h"

#include "hexlod/grammar/batch_expander.h"
#include "hexlod/scene/building_floors.h"
#include "hexlod/scene/demo_footprints.h"
#include "hexlod/scene/geojson_footprints.h"
#include "hexlod/scene/osm_footprints.h"

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

using grammar::CompiledGrammar;

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

bool loadBuildings(const ExpandOptions& options, const CompiledGrammar& g,
                   const std::vector<grammar::ParameterOverride>& overrides,
                   std::vector<grammar::BuildingInput>& buildings) {
    std::vector<double> heights, levels;
    if (!options.footprintsPath.empty()) {
        const std::string& path = options.footprintsPath;
        scene::ImportedFootprints imported;
        std::string error;
        bool read = false;
        if (path.ends_with(".geojson") || path.ends_with(".json")) {
            read = scene::readGeoJsonFootprints(path, imported, error);
        } else if (path.ends_with(".osm") || path.ends_with(".pbf") || path.ends_with(".osm.bz2")) {
            read = scene::readOsmFootprints(path, imported, error);
        } else {
            error = "'" + path +
                    "': unknown footprint format (expected .geojson, .json, .osm, .osm.pbf or .osm.bz2)";
        }
        if (!read) {
            std::cerr << "hexlod expand: " << error << "\n";
            return false;
        }
        std::cerr << "imported " << imported.buildings.size() << " footprints from " << imported.features
                  << " features of " << path << "\n";
        for (const auto& [reason, count] : imported.skipped) {
            std::cerr << "  skipped " << count << " features: " << reason << "\n";
        }
        for (const auto& [reason, count] : imported.warnings) {
            std::cerr << "  kept " << count << " buildings, ignoring: " << reason << "\n";
        }
        if (!imported.attribution.empty()) std::cerr << "  data: " << imported.attribution << "\n";
        if (imported.holesIgnored > 0) {
            std::cerr << "  ignored " << imported.holesIgnored
                      << " inner rings (footprints use outer rings)\n";
        }
        buildings = std::move(imported.buildings);
        heights = std::move(imported.heights);
        levels = std::move(imported.levels);
    } else {
        buildings = scene::makeDemoFootprints({options.demoCount, options.seed, 60.0});
    }
    for (size_t i = 0; i < buildings.size(); ++i) {
        grammar::BuildingInput& b = buildings[i];
        // Imported storeys where the data has them; otherwise varied by seed like the demo city.
        const double floors =
            i < heights.size() ? scene::floorsFromImport(g, heights[i], i < levels.size() ? levels[i] : NAN)
                               : NAN;
        std::vector<grammar::ParameterOverride> mine;
        if (std::isfinite(floors)) {
            scene::appendFloors(g, floors, mine);
        } else {
            mine = scene::demoParameterOverrides(g, options.seed, b.id);
        }
        mine.insert(mine.end(), overrides.begin(), overrides.end()); // explicit --param wins
        grammar::DiagnosticList ignored;
        b.parameters = grammar::resolveParameters(g, mine, ignored);
    }
    return true;
}

} // namespace

CLI::App* registerExpandCommand(CLI::App& app, ExpandOptions& o) {
    CLI::App* cmd = app.add_subcommand("expand", "Expand a grammar over footprints into a terminal set");
    auto* scene =
        cmd->add_option("--scene", o.scenePath, "Expand every batch of a scene config (docs/scene.md)")
            ->check(CLI::ExistingFile);
    auto* grammarOption =
        cmd->add_option("--grammar", o.grammarPath, "Grammar file (.grammar)")->check(CLI::ExistingFile);
    auto* footprints = cmd->add_option("--footprints", o.footprintsPath,
                                       "Footprints: GeoJSON (.geojson, .json) or OpenStreetMap buildings "
                                       "(.osm, .osm.pbf, .osm.bz2)")
                           ->check(CLI::ExistingFile);
    auto* demo = cmd->add_option("--demo", o.demoCount, "Expand N procedural demo footprints")
                     ->check(CLI::Range(1u, 10000000u));
    footprints->excludes(demo);
    auto* param = cmd->add_option("--param", o.params, "Override a parameter for every building: name=value");
    scene->excludes(grammarOption)->excludes(footprints)->excludes(demo)->excludes(param);
    cmd->add_option("--threads", o.threads, "Worker threads (default: all)")->check(CLI::Range(1u, 1024u));
    cmd->add_option("--repeat", o.repeat, "Time the expansion N times and report the median")
        ->check(CLI::Range(1u, 1000u));
    cmd->add_option("--seed", o.seed, "Scene seed for footprints and stochastic rules");
    cmd->add_option("--out", o.outPath, "Write the terminal set to this file (with --grammar)")
        ->excludes(scene);
    cmd->add_flag("--stats", o.stats, "Print statistics");
    cmd->add_flag("--json", o.json, "Print statistics as one JSON object");
    return cmd;
}

int runExpandCommand(const ExpandOptions& options) {
    if (!options.scenePath.empty()) return runSceneExpansion(options);
    if (options.grammarPath.empty() || (options.demoCount == 0 && options.footprintsPath.empty())) {
        std::cerr << "hexlod expand: give --scene S, or --grammar G with --demo N or --footprints F\n";
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
    const bool errors = reportIssues(g, timing.result);
    if (!options.outPath.empty()) {
        std::string error;
        if (!writeTerminalSetFile(options.outPath, timing.result.terminals, error)) {
            std::cerr << "hexlod expand: " << error << "\n";
            return 1;
        }
    }
    const nlohmann::json stats =
        batchStats(g, options.grammarPath, buildings.size(), threads, options.repeat, timing);
    if (options.json) {
        std::cout << stats.dump(2) << "\n";
    } else if (options.stats || options.outPath.empty()) {
        printBatchStats(stats);
    }
    return errors ? 1 : 0;
}

} // namespace hexlod::apps
