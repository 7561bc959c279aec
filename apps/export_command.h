// `hexlod export --scene S [--journal J] -o OUT`: writes the scene with its journal's edits.
// The output's extension picks the export: .json is a scene config with the edits as
// overrides; .glb and .gltf (geometry) are a separate exporter, plugged in at exportTo().
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace hexlod::apps {

struct ExportOptions {
    std::string scenePath;
    std::string journalPath; // default: beside the scene
    std::string outPath;
};

CLI::App* registerExportCommand(CLI::App& app, ExportOptions& options);
int runExportCommand(const ExportOptions& options);

} // namespace hexlod::apps
