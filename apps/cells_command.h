// `hexlod cells`: builds a scene and its cell index, and reports the cells, the batches, the
// spread of buildings over cells, and what building them cost in time and memory.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace hexlod::apps {

struct CellsOptions {
    std::string scenePath;
    bool stats = false;
    bool json = false;
    bool generate = false;
    uint32_t maxCells = 0; // with generate: 0 means every cell
};

CLI::App* registerCellsCommand(CLI::App& app, CellsOptions& options);
int runCellsCommand(const CellsOptions& options);

} // namespace hexlod::apps
