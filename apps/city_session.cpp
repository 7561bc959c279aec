#include "city_session.h"

#include "hexlod/render/framebuffer.h"
#include "hexlod/scene/scene_builder.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>

namespace hexlod::apps {

uint64_t peakRssBytes() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
        if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024; // reported in kB
    }
    return 0;
}

int openCity(const std::string& command, const std::string& scenePath, CitySession& out) {
    std::string error;
    if (!scene::loadSceneConfig(scenePath, out.config, error)) {
        std::cerr << "hexlod " << command << ": " << error << "\n";
        return 2;
    }
    scene::BuiltScene built;
    if (!scene::buildScene(out.config, built, error)) {
        std::cerr << "hexlod " << command << ": " << error << "\n";
        return 2;
    }
    out.notes = built.notes; // the scene builder's, "vegetation: off (no trees)" among them
    try {
        out.catalog = std::make_unique<cells::BatchCatalog>(std::move(built));
    } catch (const std::exception& e) {
        std::cerr << "hexlod " << command << ": " << out.config.file << ": " << e.what() << "\n";
        return 1;
    }
    cache::CacheOptions caching;
    caching.memoryBudgetBytes = out.config.cache.memoryBytes;
    caching.diskBudgetBytes = out.config.cache.diskBytes;
    caching.diskPath = out.config.cache.diskPath;
    try {
        out.cache = std::make_unique<cache::TerminalSetCache>(caching);
    } catch (const std::exception& e) {
        std::cerr << "hexlod " << command << ": cache.disk_path: " << e.what() << "\n";
        return 2;
    }
    out.meshes = sceneMeshLibrary(*out.catalog);
    for (const std::string& note : out.meshes->notes()) out.notes.push_back("meshes: " + note);
    return 0;
}

std::unique_ptr<render::TerminalMeshLibrary> sceneMeshLibrary(const cells::BatchCatalog& catalog) {
    std::vector<const grammar::CompiledGrammar*> grammars;
    for (uint32_t g = 0; g < catalog.index().grammarCount(); ++g)
        grammars.push_back(&catalog.grammar(g).grammar);
    std::vector<render::GltfShapeSource> sources;
    for (const scene::ShapeSource& s : catalog.scene().config.shapes) sources.push_back({s.shape, s.gltf});
    return std::make_unique<render::TerminalMeshLibrary>(grammars, sources);
}

lod::SceneImpostorOptions sceneImpostorOptions(const RenderSetup& setup) {
    lod::SceneImpostorOptions options;
    options.facadeLayout = {impostor::ViewSphere::Hemisphere, setup.impostorGrid, setup.impostorResolution,
                            2};
    // Trees are larger on screen than a window or a ledge: their views get twice the texels.
    options.treeLayout = {impostor::ViewSphere::FullSphere, setup.impostorGrid,
                          std::min<uint32_t>(2 * setup.impostorResolution, 1024), 2};
    options.storeDirectory = setup.impostorStore;
    if (setup.progress) {
        options.progress = [](size_t done, size_t total, const std::string& name) {
            const int width = 30, filled = int(width * done / std::max<size_t>(total, 1));
            std::fprintf(stderr, "\rbaking [%.*s%*s] %zu/%zu %-24.24s", filled,
                         "==============================", width - filled, "", done, total, name.c_str());
            if (done == total) std::fputc('\n', stderr);
        };
    }
    return options;
}

void appendImpostorNotes(const lod::SceneImpostorReport& report, std::vector<std::string>& notes) {
    notes.push_back(report.summary());
    for (const lod::BakedShapeReport& shape : report.shapes) {
        if (!shape.note.empty()) notes.push_back("impostors: " + shape.name + ": " + shape.note);
    }
}

std::string glContextNote(const render::GlContext& gl) {
    const render::GlContextInfo& info = gl.info();
    return std::string("gl: ") + render::glBackendName(info.backend) + ", " + info.renderer + ", " +
           info.version + (info.software ? " (software: frame times are not GPU figures)" : "");
}

int openRenderer(const std::string& command, const RenderSetup& setup, CitySession& session) {
    render::GlContextResult gl = render::createGlContext({setup.backend, true});
    if (!gl.context) {
        std::cerr << "hexlod " << command << ": " << gl.error() << "\n";
        return 1;
    }
    session.gl = std::move(gl.context);
    if (std::string why = render::unsupportedSamples(setup.samples); !why.empty()) {
        std::cerr << "hexlod " << command << ": " << why << "\n";
        return 1;
    }
    session.notes.push_back(glContextNote(*session.gl));
    if (!setup.impostors) {
        session.notes.push_back("impostors: off (every terminal draws at LOD4)");
        return 0;
    }
    const lod::SceneImpostorOptions options = sceneImpostorOptions(setup);
    std::string error;
    if (!lod::bakeSceneImpostors(session.catalog->scene(), *session.meshes, options, session.impostors,
                                 session.impostorReport, error)) {
        std::cerr << "hexlod " << command << ": impostors: " << error << "\n";
        return 1;
    }
    appendImpostorNotes(session.impostorReport, session.notes);
    return 0;
}

} // namespace hexlod::apps
