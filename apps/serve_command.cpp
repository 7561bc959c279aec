#include "serve_command.h"

#include "serve_shape_assets.h"

#include "hexlod/scene/scene_builder.h"
#include "hexlod/server/edit_journal.h"
#include "hexlod/server/server.h"

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <unistd.h>

namespace hexlod::apps {

CLI::App* registerServeCommand(CLI::App& app, ServeOptions& o) {
    CLI::App* cmd = app.add_subcommand("serve", "Serve a scene over HTTP: the API, the web viewer, edits");
    cmd->add_option("--scene", o.scenePath, "Scene config (docs/scene.md)")->capture_default_str();
    cmd->add_option("--bind", o.bind, "Address to listen on; anything but loopback needs --token")
        ->capture_default_str();
    cmd->add_option("--port", o.port, "TCP port; 0 picks a free one")->capture_default_str();
    cmd->add_option("--journal", o.journalPath,
                    "Edit journal (default: <scene folder>/<scene name>.edits.jsonl)");
    cmd->add_flag("--journal-repair", o.journalRepair,
                  "Move corrupt journal lines to <journal>.rejected instead of refusing to start");
    cmd->add_option("--threads", o.threads, "I/O threads")
        ->check(CLI::Range(1u, 256u))
        ->capture_default_str();
    cmd->add_option("--generators", o.generators, "Batches generated at once")
        ->check(CLI::Range(1u, 64u))
        ->capture_default_str();
    cmd->add_option("--token", o.token,
                    "Edit token (default: $HEXLOD_TOKEN); edits then need 'Authorization: Bearer T'");
    cmd->add_option("--web-root", o.webRoot, "Folder of the web viewer's files")->capture_default_str();
    cmd->add_option("--payload-cache-mb", o.payloadCacheMb,
                    "Encoded payload cache: 3/4 for terminal sets, 1/4 for extruded sets")
        ->check(CLI::Range(1u, 1u << 20))
        ->capture_default_str();
    cmd->add_option("--cache-mb", o.cacheMb,
                    "Decoded terminal-set cache (default: the scene's cache.memory_mb)")
        ->check(CLI::Range(1u, 1u << 24));
    cmd->add_option("--rate-limit", o.rateLimit,
                    "Requests per second per client address (burst: twice that); 0: off")
        ->check(CLI::Range(0.0, 1e9))
        ->capture_default_str();
    cmd->add_flag("!--no-impostors", o.impostors,
                  "Serve terminal meshes only: no GL context, no impostor bake");
    cmd->add_option("--gl", o.render.backend,
                    "GL backend for the impostor bake: auto, egl-device, egl-surfaceless, osmesa")
        ->capture_default_str();
    cmd->add_option("--impostor-grid", o.render.impostorGrid, "Impostor views per side (2 to 32)")
        ->capture_default_str();
    cmd->add_option("--impostor-res", o.render.impostorResolution,
                    "Texels per impostor view side (16 to 1024)")
        ->capture_default_str();
    cmd->add_option("--impostor-store", o.render.impostorStore,
                    "Folder of baked impostors (EXR, shared with hexlod bake); empty: bake in memory")
        ->capture_default_str();
    return cmd;
}

int runServeCommand(ServeOptions o) {
    if (o.token.empty())
        if (const char* env = std::getenv("HEXLOD_TOKEN")) o.token = env;
    server::ServerOptions serverOptions;
    serverOptions.bind = o.bind;
    serverOptions.port = o.port;
    serverOptions.threads = o.threads;
    serverOptions.token = o.token;
    serverOptions.webRoot = o.webRoot;
    serverOptions.rateLimit = o.rateLimit;
    serverOptions.rateBurst = 2.0 * o.rateLimit;
    serverOptions.log = [](const std::string& line) { std::cerr << "hexlod serve: " << line << std::endl; };
    std::string error;
    if (!server::checkBindPolicy(serverOptions, error)) {
        std::cerr << "hexlod serve: " << error << "\n";
        return 2;
    }
    ServeAssetSetup assetSetup;
    if (!makeRenderSetup(o.render, assetSetup.render, error)) {
        std::cerr << "hexlod serve: " << error << "\n";
        return 2;
    }
    assetSetup.render.impostors = o.impostors;
    assetSetup.render.progress = isatty(STDERR_FILENO) != 0; // a bar in a terminal, not in a log file

    scene::SceneConfig config;
    if (!scene::loadSceneConfig(o.scenePath, config, error)) {
        std::cerr << "hexlod serve: " << error << "\n";
        return 2;
    }
    std::cerr << "hexlod serve: building scene " << config.name << " from " << o.scenePath << std::endl;
    scene::BuiltScene built;
    if (!scene::buildScene(config, built, error)) {
        std::cerr << "hexlod serve: " << error << "\n";
        return 1;
    }
    for (const std::string& credit : built.attributions) std::cerr << "hexlod serve: data " << credit << "\n";

    cache::CacheOptions cacheOptions;
    cacheOptions.memoryBudgetBytes = o.cacheMb ? uint64_t(o.cacheMb) << 20 : config.cache.memoryBytes;
    cacheOptions.diskBudgetBytes = config.cache.diskBytes;
    cacheOptions.diskPath = config.cache.diskPath;
    server::ServiceOptions serviceOptions;
    serviceOptions.journalPath =
        o.journalPath.empty() ? server::defaultJournalPath(o.scenePath) : o.journalPath;
    serviceOptions.journalRepair = o.journalRepair;
    serviceOptions.generationWorkers = o.generators;
    const uint64_t payloadBytes = uint64_t(o.payloadCacheMb) << 20;
    serviceOptions.terminalPayloadBytes = payloadBytes / 4 * 3;
    serviceOptions.extrudedPayloadBytes = payloadBytes / 4;
    serviceOptions.editsNeedToken = !o.token.empty();
    std::vector<std::string> log;
    std::unique_ptr<server::SceneService> service;
    try {
        service = server::SceneService::create(std::move(built), cacheOptions, serviceOptions, log, error);
    } catch (const std::exception& e) {
        error = e.what();
    }
    for (const std::string& line : log) std::cerr << "hexlod serve: " << line << "\n";
    if (!service) {
        std::cerr << "hexlod serve: " << error << "\n";
        return 1;
    }

    ServeAssets assets = service->withCatalog(
        [&](const cells::BatchCatalog& catalog) { return buildShapeAssets(catalog, assetSetup); });
    for (const std::string& line : assets.shapes.notes) std::cerr << "hexlod serve: " << line << "\n";
    service->attachShapeAssets(std::move(assets.shapes));
    if (assets.bakery) service->attachSpeciesBakery(std::move(assets.bakery));

    server::Server httpServer(*service, serverOptions);
    if (!httpServer.start(error)) {
        std::cerr << "hexlod serve: " << error << "\n";
        return 1;
    }
    httpServer.stopOnSignals();
    std::cerr << "hexlod serve: " << o.threads << " I/O threads, edits "
              << (o.token.empty() ? "open" : "need the token") << ", web viewer from " << o.webRoot
              << "; Ctrl-C stops" << std::endl;
    // Tests and scripts read this line for the real port.
    std::cout << "hexlod serve: viewer at " << httpServer.url() << std::endl;
    httpServer.waitForStop();
    service->stop();
    std::cerr << "hexlod serve: stopped; journal " << serviceOptions.journalPath
              << " holds every acknowledged edit" << std::endl;
    return 0;
}

} // namespace hexlod::apps
