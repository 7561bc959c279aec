// What the rendering commands (walk, bench, bake) open before their work: the scene and its
// cell index, the terminal meshes, a GL context and the scene's impostors. Each step reports
// what it started and why ("vegetation: off (no trees)", "impostors: 9 of 31 declared shapes
// baked"), so a run says what it left out.
#pragma once

#include "hexlod/cache/terminal_set_cache.h"
#include "hexlod/cells/batch_catalog.h"
#include "hexlod/lod/scene_impostors.h"
#include "hexlod/render/gl_context.h"
#include "hexlod/render/terminal_mesh_library.h"

#include <memory>
#include <string>
#include <vector>

namespace hexlod::apps {

struct CitySession {
    scene::SceneConfig config;
    std::unique_ptr<cells::BatchCatalog> catalog;
    std::unique_ptr<cache::TerminalSetCache> cache;
    std::unique_ptr<render::TerminalMeshLibrary> meshes;
    std::unique_ptr<render::GlContext> gl;
    lod::SceneImpostors impostors;
    lod::SceneImpostorReport impostorReport;
    std::vector<std::string> notes; // what was started, skipped or left out, and why
};

// Loads and builds the scene, indexes it and builds its mesh library. On failure prints
// "hexlod <command>: <error>" and returns the exit code (2: bad config, 1: other), else 0.
int openCity(const std::string& command, const std::string& scenePath, CitySession& out);

struct RenderSetup {
    render::GlBackend backend = render::GlBackend::Auto;
    uint32_t impostorGrid = 8;
    uint32_t impostorResolution = 32; // texels per facade view; tree views get twice as many
    std::string impostorStore;        // empty: bake in memory only
    bool impostors = true;
    bool progress = false; // a progress bar on stderr while baking
    uint32_t samples = 1;  // per pixel, checked against the GL before anything is baked
};

// Creates the GL context and bakes (or loads) the impostors the scene uses. Same contract.
int openRenderer(const std::string& command, const RenderSetup& setup, CitySession& session);

// The scene's terminal meshes: a mesh per declared shape of every grammar, glTF where the
// config maps a shape to a file.
std::unique_ptr<render::TerminalMeshLibrary> sceneMeshLibrary(const cells::BatchCatalog& catalog);
// The impostor layouts and store of a setup.
lod::SceneImpostorOptions sceneImpostorOptions(const RenderSetup& setup);
// The report's summary line and a line per shape with a note.
void appendImpostorNotes(const lod::SceneImpostorReport& report, std::vector<std::string>& notes);
// "gl: <backend>, <renderer>, <version>[ (software: ...)]".
std::string glContextNote(const render::GlContext& gl);

// Peak resident set of the process (VmHWM); 0 where /proc is missing.
uint64_t peakRssBytes();

} // namespace hexlod::apps
