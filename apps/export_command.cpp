#include "export_command.h"

#include "hexlod/server/edit_journal.h"
#include "hexlod/server/scene_export.h"

#include <filesystem>
#include <iostream>

namespace hexlod::apps {
namespace {

int exportSceneConfig(const ExportOptions& o, const scene::SceneConfig& config) {
    const std::string journal =
        o.journalPath.empty() ? server::defaultJournalPath(o.scenePath) : o.journalPath;
    server::ExportReport report;
    std::string error;
    if (!server::exportEditedScene(config, journal, o.outPath, report, error)) {
        std::cerr << "hexlod export: " << error << "\n";
        return 1;
    }
    for (const std::string& note : report.notes) std::cerr << "hexlod export: " << note << "\n";
    std::cout << "hexlod export: " << o.outPath << ": " << report.entries << " journal entries, "
              << report.editedBuildings << " edited buildings in " << report.overrides << " overrides, "
              << report.editedSpecies << " edited tree species\n";
    return 0;
}

} // namespace

CLI::App* registerExportCommand(CLI::App& app, ExportOptions& o) {
    CLI::App* cmd = app.add_subcommand("export", "Write a scene with its journal's edits applied");
    cmd->add_option("--scene", o.scenePath, "Scene config (docs/scene.md)")->required();
    cmd->add_option("--journal", o.journalPath, "Edit journal (default: beside the scene, as hexlod serve)");
    cmd->add_option("-o,--out", o.outPath, "Output: a .json scene config")->required();
    return cmd;
}

int runExportCommand(const ExportOptions& o) {
    std::string extension = std::filesystem::path(o.outPath).extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (extension == ".glb" || extension == ".gltf") {
        std::cerr << "hexlod export: glTF export is not available in this build\n";
        return 2;
    }
    if (extension != ".json") {
        std::cerr << "hexlod export: unknown output type '" << extension
                  << "' (expected .json, .glb or .gltf)\n";
        return 2;
    }
    scene::SceneConfig config;
    std::string error;
    if (!scene::loadSceneConfig(o.scenePath, config, error)) {
        std::cerr << "hexlod export: " << error << "\n";
        return 2;
    }
    return exportSceneConfig(o, config);
}

} // namespace hexlod::apps
