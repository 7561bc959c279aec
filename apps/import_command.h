// `hexlod import`: reads building footprints from GeoJSON or OpenStreetMap data and writes a
// scene config (docs/scene.md) that builds a city from them.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace hexlod::apps {

struct ImportOptions {
    std::string inputPath;
    std::string outPath;
    std::string grammar; // a .grammar file, or the name of a shipped grammar
    bool json = false;
};

CLI::App* registerImportCommand(CLI::App& app, ImportOptions& options);
int runImportCommand(const ImportOptions& options);

} // namespace hexlod::apps
