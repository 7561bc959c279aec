// `hexlod walk`: renders a camera path headless through the LOD system and reports every
// frame: CPU time per stage, frame time, triangles, draws, terminals and cells per LOD and
// bytes resident; optionally PNG frames, and a summary with a frame-time plot.
#pragma once

#include "render_options.h"

#include <CLI/CLI.hpp>

#include <string>

namespace hexlod::apps {

struct WalkOptions {
    std::string scenePath, pathPath, outDir, profilePath, mode = "lod";
    uint32_t frames = 60;
    bool reference = false, png = false, json = false;
    bool timePasses = false; // --time-passes
    bool keepHidden = false; // --keep-hidden
    RenderOptions render;
};

CLI::App* registerWalkCommand(CLI::App& app, WalkOptions& options);
int runWalkCommand(const WalkOptions& options);

} // namespace hexlod::apps
