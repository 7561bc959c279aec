#include "bake_command.h"

#include "contact_sheet.h"
#include "render_options.h"

#include "hexlod/render/image_io.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>

namespace hexlod::apps {

CLI::App* registerBakeCommand(CLI::App& app, BakeOptions& o) {
    CLI::App* cmd = app.add_subcommand("bake", "Bake the impostors a scene uses into the EXR store");
    cmd->add_option("--scene", o.scenePath, "Scene config (docs/scene.md)")->required();
    cmd->add_option("--grid", o.grid, "Views per side: N x N views per shape (2 to 32)");
    cmd->add_option("--res", o.resolution, "Texels per view side (16 to 1024)");
    cmd->add_option("--store", o.storeDir, "Folder of the content-addressed EXR store");
    cmd->add_option("--show", o.show,
                    "Write a contact sheet of this shape's views (a shape or tree:<species>)");
    cmd->add_option("-o,--output", o.output, "Contact sheet PNG (with --show)");
    cmd->add_option("--gl", o.backend, "GL backend: auto, egl-device, egl-surfaceless, osmesa");
    cmd->add_flag("--json", o.json, "Print the report as one JSON object");
    return cmd;
}

int runBakeCommand(const BakeOptions& o) {
    if (!o.show.empty() && o.output.empty()) {
        std::cerr << "hexlod bake: --show needs -o sheet.png\n";
        return 2;
    }
    RenderOptions render;
    render.backend = o.backend;
    render.impostorGrid = o.grid;
    render.impostorResolution = o.resolution;
    render.impostorStore = o.storeDir;
    RenderSetup setup;
    std::string error;
    if (!makeRenderSetup(render, setup, error)) {
        std::cerr << "hexlod bake: " << error << "\n";
        return 2;
    }
    setup.progress = !o.json;
    CitySession session;
    if (int code = openCity("bake", o.scenePath, session)) return code;
    if (int code = openRenderer("bake", setup, session)) return code;
    const lod::SceneImpostorReport& report = session.impostorReport;

    if (!o.show.empty()) {
        const impostor::ImpostorAtlas* atlas = nullptr;
        for (const auto* list : {&session.impostors.facades, &session.impostors.species})
            for (const impostor::ImpostorAtlas& a : *list)
                if (a.shape == o.show) atlas = &a;
        if (!atlas) {
            std::cerr << "hexlod bake: --show: no impostor named '" << o.show << "' in this scene; it has:";
            for (const auto& shape : report.shapes) std::cerr << " " << shape.name;
            std::cerr << "\n";
            return 2;
        }
        if (!render::writePng(o.output, contactSheet(*atlas), error)) {
            std::cerr << "hexlod bake: " << error << "\n";
            return 1;
        }
    }
    // Terminal shapes and tree species are counted apart, as the report names them.
    uint32_t baked = 0, loaded = 0, species = 0;
    nlohmann::json shapes = nlohmann::json::array();
    for (const lod::BakedShapeReport& shape : report.shapes) {
        const bool made = shape.note.rfind("not baked", 0) != 0;
        if (shape.shape < 0)
            species += made;
        else
            (shape.outcome == lod::BakeOutcome::Loaded ? loaded : baked) += made;
        const char* outcome = shape.outcome == lod::BakeOutcome::Loaded    ? "loaded"
                              : shape.outcome == lod::BakeOutcome::Rebaked ? "rebaked"
                                                                           : "baked";
        shapes.push_back({{"name", shape.name},
                          {"grammar", shape.grammar},
                          {"outcome", outcome},
                          {"seconds", shape.seconds},
                          {"file_bytes", shape.fileBytes},
                          {"gpu_bytes", shape.gpuBytes},
                          {"note", shape.note}});
    }
    if (o.json) {
        nlohmann::json out = {{"scene", session.config.name},
                              {"shapes_baked", baked},
                              {"shapes_loaded", loaded},
                              {"shapes_skipped_unused", report.skippedUnused},
                              {"shapes_declared", report.declaredShapes},
                              {"tree_species", species},
                              {"bytes", report.fileBytes},
                              {"gpu_bytes", report.gpuBytes},
                              {"seconds", report.seconds},
                              {"grid", o.grid},
                              {"resolution", o.resolution},
                              {"store", o.storeDir},
                              {"shapes", shapes},
                              {"notes", session.notes}};
        std::printf("%s\n", out.dump().c_str());
        return 0;
    }
    for (const std::string& note : session.notes) std::printf("%s\n", note.c_str());
    std::printf("%-28s %-8s %9s %12s %12s\n", "shape", "outcome", "seconds", "file bytes", "gpu bytes");
    for (const auto& shape : shapes) {
        std::printf("%-28s %-8s %9.3f %12llu %12llu\n", shape["name"].get<std::string>().c_str(),
                    shape["outcome"].get<std::string>().c_str(), shape["seconds"].get<double>(),
                    (unsigned long long)shape["file_bytes"].get<uint64_t>(),
                    (unsigned long long)shape["gpu_bytes"].get<uint64_t>());
    }
    std::printf(
        "shapes baked %u, loaded %u, skipped (unused) %u of %u declared; %u tree species; %.1f MB on disk, "
        "%.1f MB on the GPU, %.2f s\n",
        baked, loaded, report.skippedUnused, report.declaredShapes, species, double(report.fileBytes) / 1e6,
        double(report.gpuBytes) / 1e6, report.seconds);
    return 0;
}

} // namespace hexlod::apps
