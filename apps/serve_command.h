// `hexlod serve`: the streaming service on a scene (the README's main job): builds the scene,
// replays its edit journal, serves the HTTP API and the web viewer until SIGINT or SIGTERM.
#pragma once

#include "render_options.h"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace hexlod::apps {

struct ServeOptions {
    std::string scenePath = "configs/default.json";
    std::string bind = "127.0.0.1";
    uint16_t port = 8080;
    std::string journalPath; // default: beside the scene (server::defaultJournalPath)
    bool journalRepair = false;
    uint32_t threads = 2;
    uint32_t generators = 2;
    std::string token; // default: $HEXLOD_TOKEN
    std::string webRoot = "web/dist";
    uint32_t payloadCacheMb = 512;
    uint32_t cacheMb = 0; // decoded terminal sets; 0: the scene's cache.memory_mb
    double rateLimit = 1000.0;
    // Shape assets (serve_shape_assets.h); the store is shared with `hexlod bake`.
    bool impostors = true;
    RenderOptions render{.impostorStore = "out/impostors"};
};

CLI::App* registerServeCommand(CLI::App& app, ServeOptions& options);
int runServeCommand(ServeOptions options);

} // namespace hexlod::apps
