#include "export_command.h"

#include "city_gltf_export.h"

#include "hexlod/cells/batch_catalog.h"
#include "hexlod/scene/scene_builder.h"
#include "hexlod/server/edit_journal.h"
#include "hexlod/server/scene_export.h"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

namespace hexlod::apps {
namespace {

// "q,r" with whole numbers; false for anything else.
bool parseCell(const std::string& text, cells::HexCoord& out) {
    const size_t comma = text.find(',');
    if (comma == std::string::npos) return false;
    const auto number = [](std::string_view s, int32_t& v) {
        const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        return ec == std::errc() && end == s.data() + s.size() && !s.empty();
    };
    return number(std::string_view(text).substr(0, comma), out.q) &&
           number(std::string_view(text).substr(comma + 1), out.r);
}

// A .json output: the scene config with the journal's edits as overrides (server/scene_export.h).
int runSceneConfigExport(const ExportOptions& o) {
    scene::SceneConfig config;
    std::string error;
    if (!scene::loadSceneConfig(o.scenePath, config, error)) {
        std::cerr << "hexlod export: " << error << "\n";
        return 2;
    }
    const std::string journal = o.journal.empty() ? server::defaultJournalPath(o.scenePath) : o.journal;
    server::ExportReport report;
    if (!server::exportEditedScene(config, journal, o.output, report, error)) {
        std::cerr << "hexlod export: " << error << "\n";
        return 1;
    }
    for (const std::string& note : report.notes) std::cerr << "hexlod export: " << note << "\n";
    std::cout << "hexlod export: " << o.output << ": " << report.entries << " journal entries, "
              << report.editedBuildings << " edited buildings in " << report.overrides << " overrides, "
              << report.editedSpecies << " edited tree species\n";
    return 0;
}

void printReport(const CityExportReport& r, const std::string& output, bool flatten) {
    std::printf("wrote        %s (%.1f MB, %s)\n", output.c_str(), double(r.bytes) / 1e6,
                flatten ? "flattened" : "EXT_mesh_gpu_instancing");
    std::printf("cells        %u (%u batches), origin %.3f %.3f %.3f\n", r.cells, r.batches, r.origin.x,
                r.origin.y, r.origin.z);
    std::printf("terminals    %llu as %llu instances of %u terminal meshes\n",
                (unsigned long long)r.terminals, (unsigned long long)r.instances, r.terminalMeshes);
    std::printf("triangles    %llu (base volumes %llu), %u glTF meshes\n", (unsigned long long)r.triangles,
                (unsigned long long)r.baseVolumeTriangles, r.gltfMeshes);
    std::printf("time         %.3f s\n", r.seconds);
}

} // namespace

CLI::App* registerExportCommand(CLI::App& app, ExportOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "export",
        "Write a scene's full detail as glTF (.glb, .gltf) or its config with edits applied (.json)");
    cmd->add_option("--scene", o.scenePath, "Scene config (docs/scene.md)")->required();
    cmd->add_option("-o,--output", o.output, "Output file: .glb or .gltf (glTF 2.0), .json (scene config)")
        ->required();
    cmd->add_option(
           "--cells", o.cells,
           "Cells to export as q,r (repeat the option or list several; default: every occupied cell)")
        ->expected(1, -1)
        ->allow_extra_args();
    cmd->add_option(
        "--journal", o.journal,
        "With a .json output: the edit journal to apply (default: beside the scene, as hexlod serve)");
    cmd->add_flag("--flatten", o.flatten,
                  "Bake every instance into plain meshes instead of EXT_mesh_gpu_instancing");
    cmd->add_option("--max-bytes", o.maxBytes,
                    "Refuse an export whose buffer would pass N bytes (default: 4 GiB for .glb)")
        ->check(CLI::Range(uint64_t(1), uint64_t(1) << 40));
    cmd->add_flag("--json", o.json, "Print the report as one JSON object");
    return cmd;
}

int runExportCommand(const ExportOptions& options) {
    const std::string extension = std::filesystem::path(options.output).extension().string();
    if (extension == ".json") return runSceneConfigExport(options);
    if (extension != ".glb" && extension != ".gltf") {
        std::cerr << "hexlod export: " << options.output << ": the output must end in .glb, .gltf or .json\n";
        return 2;
    }
    CityExportOptions exportOptions;
    exportOptions.output = options.output;
    exportOptions.flatten = options.flatten;
    exportOptions.maxBytes = options.maxBytes;
    for (const std::string& text : options.cells) {
        cells::HexCoord cell;
        if (!parseCell(text, cell)) {
            std::cerr << "hexlod export: --cells: '" << text
                      << "' is not a cell; write q,r (for example 0,-1)\n";
            return 2;
        }
        exportOptions.cells.push_back(cell);
    }
    scene::SceneConfig config;
    std::string error;
    if (!scene::loadSceneConfig(options.scenePath, config, error)) {
        std::cerr << "hexlod export: " << error << "\n";
        return 2;
    }
    scene::BuiltScene built;
    if (!scene::buildScene(config, built, error)) {
        std::cerr << "hexlod export: " << error << "\n";
        return 2;
    }
    std::optional<cells::BatchCatalog> catalog;
    try {
        catalog.emplace(std::move(built));
    } catch (const std::exception& e) {
        std::cerr << "hexlod export: " << config.file << ": " << e.what() << "\n";
        return 1;
    }
    std::vector<const grammar::CompiledGrammar*> grammars;
    for (uint32_t g = 0; g < catalog->index().grammarCount(); ++g)
        grammars.push_back(&catalog->grammar(g).grammar);
    std::vector<render::GltfShapeSource> sources;
    for (const scene::ShapeSource& s : config.shapes) sources.push_back({s.shape, s.gltf});
    const render::TerminalMeshLibrary library(grammars, sources);
    for (const std::string& note : library.notes()) std::cerr << "hexlod export: " << note << "\n";

    const CityExportReport report = exportCityGltf(*catalog, library, exportOptions);
    for (const std::string& warning : report.warnings) std::cerr << "hexlod export: " << warning << "\n";
    if (!report.ok) {
        std::cerr << "hexlod export: " << options.output << ": " << report.error << "\n";
        return report.error.find("holds no buildings") != std::string::npos ? 2 : 1;
    }
    if (options.json) {
        nlohmann::json j = {
            {"output", options.output},
            {"format", extension.substr(1)},
            {"flatten", options.flatten},
            {"bytes", report.bytes},
            {"cells", report.cells},
            {"batches", report.batches},
            {"terminals", report.terminals},
            {"instances", report.instances},
            {"meshes", report.gltfMeshes},
            {"terminal_meshes", report.terminalMeshes},
            {"triangles", report.triangles},
            {"base_volume_triangles", report.baseVolumeTriangles},
            {"instances_per_mesh", report.instancesPerMesh},
            {"origin", {report.origin.x, report.origin.y, report.origin.z}},
            {"mesh_notes", library.notes()},
            {"seconds", report.seconds},
        };
        std::cout << j.dump(2) << "\n";
    } else {
        printReport(report, options.output, options.flatten);
    }
    return 0;
}

} // namespace hexlod::apps
