// `hexlod expand`: expands a grammar over footprints and reports terminal-set statistics.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace hexlod::apps {

struct ExpandOptions {
    std::string scenePath;
    std::string grammarPath;
    std::string footprintsPath;
    uint32_t demoCount = 0;
    std::vector<std::string> params;
    uint32_t threads = 0; // 0: all hardware threads
    uint32_t repeat = 1;
    uint64_t seed = 1;
    std::string outPath;
    bool stats = false;
    bool json = false;
};

CLI::App* registerExpandCommand(CLI::App& app, ExpandOptions& options);
int runExpandCommand(const ExpandOptions& options);

} // namespace hexlod::apps
