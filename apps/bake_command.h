// `hexlod bake`: bakes the impostors a scene uses (and only those) into the content-addressed
// EXR store, with a progress bar, time and bytes per shape; `--show SHAPE -o sheet.png` writes
// a contact sheet of one shape's views for a person to look at.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace hexlod::apps {

struct BakeOptions {
    std::string scenePath, storeDir = "out/impostors", show, output, backend = "auto";
    uint32_t grid = 8, resolution = 32;
    bool json = false;
};

CLI::App* registerBakeCommand(CLI::App& app, BakeOptions& options);
int runBakeCommand(const BakeOptions& options);

} // namespace hexlod::apps
