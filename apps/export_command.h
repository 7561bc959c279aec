// `hexlod export --scene S [--cells q,r ...] [--flatten] [--json] -o OUT`: dispatches on the
// output's extension. .glb and .gltf write the chosen cells' full detail as glTF
// (city_gltf_export.h); .json is the scene config with the edit journal applied.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace hexlod::apps {

struct ExportOptions {
    std::string scenePath;
    std::string output;
    std::vector<std::string> cells; // "q,r" each
    std::string journal;            // .json exports: the edit journal to apply
    bool flatten = false;
    bool json = false;
    uint64_t maxBytes = 0; // 0: the format's limit
};

CLI::App* registerExportCommand(CLI::App& app, ExportOptions& options);
int runExportCommand(const ExportOptions& options);

} // namespace hexlod::apps
