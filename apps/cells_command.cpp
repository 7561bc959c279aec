#include "cells_command.h"

#include "cell_generation.h"

#include "hexlod/cells/cell_index.h"
#include "hexlod/scene/scene_builder.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace hexlod::apps {
namespace {

constexpr uint32_t kBucketWidth = 50; // buildings per histogram bucket

// The process's peak resident set (VmHWM), which covers the scene and the index together;
// 0 where /proc is not available.
uint64_t peakRssBytes() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
        if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024; // reported in kB
    }
    return 0;
}

// Buildings (not trees) of each occupied cell, in cells() order.
std::vector<uint32_t> buildingsPerCell(const cells::CellIndex& index) {
    std::vector<uint32_t> counts;
    counts.reserve(index.cells().size());
    for (const cells::CellBounds& cell : index.cells()) {
        uint32_t n = 0;
        for (const cells::Batch& batch : index.batchesOf(cell.cell)) {
            if (!index.isTreeGrammar(batch.grammar)) n += static_cast<uint32_t>(batch.buildings.size());
        }
        counts.push_back(n);
    }
    return counts;
}

// Over the cells that hold buildings: a cell of park trees says nothing about the cell size.
nlohmann::json distribution(std::vector<uint32_t> counts) {
    std::erase(counts, 0u);
    if (counts.empty()) return {{"cells", 0}, {"histogram", nlohmann::json::array()}};
    std::sort(counts.begin(), counts.end());
    auto quantile = [&](double q) {
        return counts[static_cast<size_t>(q * double(counts.size() - 1) + 0.5)];
    };
    uint64_t total = 0;
    std::vector<uint64_t> buckets(counts.back() / kBucketWidth + 1, 0);
    for (uint32_t n : counts) {
        total += n;
        ++buckets[n / kBucketWidth];
    }
    nlohmann::json histogram = nlohmann::json::array();
    for (size_t b = 0; b < buckets.size(); ++b) {
        histogram.push_back(
            {{"from", b * kBucketWidth}, {"to", (b + 1) * kBucketWidth - 1}, {"cells", buckets[b]}});
    }
    return {{"cells", counts.size()},  {"min", counts.front()},
            {"median", quantile(0.5)}, {"mean", double(total) / double(counts.size())},
            {"p95", quantile(0.95)},   {"max", counts.back()},
            {"histogram", histogram}};
}

void printCells(const cells::CellIndex& index, const std::vector<uint32_t>& perCell) {
    std::printf("%8s %8s %10s %8s %8s %10s %10s\n", "q", "r", "buildings", "trees", "batches", "z_min",
                "z_max");
    for (size_t i = 0; i < index.cells().size(); ++i) {
        const cells::CellBounds& cell = index.cells()[i];
        const std::span<const cells::Batch> batches = index.batchesOf(cell.cell);
        size_t members = 0;
        for (const cells::Batch& batch : batches) members += batch.buildings.size();
        std::printf("%8d %8d %10u %8zu %8zu %10.1f %10.1f\n", cell.cell.q, cell.cell.r, perCell[i],
                    members - perCell[i], batches.size(), cell.zMin, cell.zMax);
    }
}

void printStats(const nlohmann::json& s) {
    const nlohmann::json& d = s["buildings_per_cell"];
    std::printf("scene        %s: %llu buildings, %llu trees\n", s["scene"].get<std::string>().c_str(),
                (unsigned long long)s["buildings"], (unsigned long long)s["trees"]);
    std::printf("cells        %llu of %.0f m (%llu with buildings), %llu batches\n",
                (unsigned long long)s["cells"], s["cell_size"].get<double>(), (unsigned long long)d["cells"],
                (unsigned long long)s["batches"]);
    if (d.contains("median")) {
        std::printf("per cell     buildings min %llu, median %llu, mean %.1f, p95 %llu, max %llu\n",
                    (unsigned long long)d["min"], (unsigned long long)d["median"], d["mean"].get<double>(),
                    (unsigned long long)d["p95"], (unsigned long long)d["max"]);
        for (const nlohmann::json& bucket : d["histogram"]) {
            std::printf("  %5llu-%-5llu %6llu cells\n", (unsigned long long)bucket["from"],
                        (unsigned long long)bucket["to"], (unsigned long long)bucket["cells"]);
        }
    }
    std::printf("index        %.2f MB\n", s["index_bytes"].get<double>() / 1e6);
    std::printf("time         %.3f s (scene %.3f s, index %.3f s), peak RSS %.1f MB\n",
                s["seconds"].get<double>(), s["scene_seconds"].get<double>(),
                s["index_seconds"].get<double>(), s["peak_rss_bytes"].get<double>() / 1e6);
    if (!s.contains("generation")) return;
    const nlohmann::json& g = s["generation"];
    auto line = [&](const char* label, const char* key, double scale, const char* unit) {
        const nlohmann::json& v = g[key];
        std::printf("%-13s median %.2f, p95 %.2f, max %.2f %s\n", label, v["median"].get<double>() * scale,
                    v["p95"].get<double>() * scale, v["max"].get<double>() * scale, unit);
    };
    std::printf("generated    %llu cells\n", g["cells_generated"].get<unsigned long long>());
    line("time/cell", "milliseconds_per_cell", 1.0, "ms");
    line("bytes/cell", "bytes_per_cell", 1e-6, "MB in memory");
    line("encoded/cell", "encoded_bytes_per_cell", 1e-6, "MB encoded");
    line("terminals", "terminals_per_cell", 1e-3, "thousand per cell");
    line("  buildings", "building_bytes_per_cell", 1e-6, "MB in memory");
    line("  buildings", "building_encoded_bytes_per_cell", 1e-6, "MB encoded");
}

} // namespace

CLI::App* registerCellsCommand(CLI::App& app, CellsOptions& o) {
    CLI::App* cmd =
        app.add_subcommand("cells", "Build a scene's cell index and report its cells and batches");
    cmd->add_option("--scene", o.scenePath, "Scene config (docs/scene.md)")->required();
    cmd->add_flag("--stats", o.stats, "Print a summary instead of one line per cell");
    cmd->add_flag("--json", o.json, "Print the summary as one JSON object");
    cmd->add_flag("--generate", o.generate, "Also expand the cells' batches: time and bytes per cell");
    cmd->add_option("--cells", o.maxCells, "With --generate: at most N cells, evenly spread (default: all)")
        ->check(CLI::Range(1u, 100000000u));
    return cmd;
}

int runCellsCommand(const CellsOptions& options) {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();
    scene::SceneConfig config;
    std::string error;
    if (!scene::loadSceneConfig(options.scenePath, config, error)) {
        std::cerr << "hexlod cells: " << error << "\n";
        return 2;
    }
    scene::BuiltScene built;
    if (!scene::buildScene(config, built, error)) {
        std::cerr << "hexlod cells: " << error << "\n";
        return 1;
    }
    for (const std::string& note : built.notes) std::cerr << "scene " << config.name << ": " << note << "\n";
    for (const std::string& credit : built.attributions) std::cerr << "data: " << credit << "\n";
    const Clock::time_point indexStart = Clock::now();
    std::optional<cells::CellIndex> index;
    try {
        index.emplace(cells::CellIndex::build(built, config.cellSize));
    } catch (const std::exception& e) {
        std::cerr << "hexlod cells: " << config.file << ": " << e.what() << "\n";
        return 1;
    }
    const Clock::time_point end = Clock::now();

    const std::vector<uint32_t> perCell = buildingsPerCell(*index);
    nlohmann::json summary = {
        {"scene", config.name},
        {"buildings", index->buildingCount()},
        {"trees", index->treeCount()},
        {"cell_size", config.cellSize},
        {"cells", index->cells().size()},
        {"batches", index->batches().size()},
        {"buildings_per_cell", distribution(perCell)},
        {"index_bytes", index->memoryBytes()},
        {"seconds", std::chrono::duration<double>(end - start).count()},
        {"scene_seconds", std::chrono::duration<double>(indexStart - start).count()},
        {"index_seconds", std::chrono::duration<double>(end - indexStart).count()},
        {"peak_rss_bytes", peakRssBytes()},
    };
    if (options.generate) summary["generation"] = generateCells(built, *index, options.maxCells);
    if (options.json) {
        std::cout << summary.dump(2) << "\n";
    } else {
        if (!options.stats) printCells(*index, perCell);
        printStats(summary);
    }
    return 0;
}

} // namespace hexlod::apps
