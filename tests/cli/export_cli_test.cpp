// `hexlod export` end to end: the JSON report on a part of the default city, the dispatch on
// the output's extension, and argument errors on stderr with exit code 2.
#include "command_runner.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace hexlod::test {
namespace {

const std::string kConfigs = HEXLOD_CONFIGS_DIR;

// The default city's first occupied cell, as `hexlod cells` lists it.
std::string firstCell() {
    const CommandResult r = runHexlod("cells --scene " + kConfigs + "/default.json");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    std::istringstream lines(r.out);
    std::string header, q, r2;
    std::getline(lines, header);
    lines >> q >> r2;
    return q + "," + r2;
}

TEST(ExportCli, HelpNamesTheOptions) {
    const CommandResult help = runHexlod("export --help");
    EXPECT_EQ(help.exitCode, 0);
    for (const char* option : {"--scene", "--cells", "--flatten", "--json", "--output", "--max-bytes"})
        EXPECT_NE(help.out.find(option), std::string::npos) << option;
}

TEST(ExportCli, JsonReportOfOneCellOfTheDefaultCity) {
    const std::string out = ::testing::TempDir() + "export-cli.glb";
    const std::string cell = firstCell();
    const CommandResult r =
        runHexlod("export --scene " + kConfigs + "/default.json --cells=" + cell + " -o " + out + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    for (const char* key :
         {"bytes", "cells", "batches", "terminals", "instances", "meshes", "terminal_meshes", "triangles",
          "base_volume_triangles", "instances_per_mesh", "origin", "seconds"})
        EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["cells"], 1);
    EXPECT_EQ(j["bytes"].get<uint64_t>(), std::filesystem::file_size(out));
    EXPECT_EQ(j["instances"], j["terminals"]);
    uint64_t perMesh = 0;
    for (const auto& [name, count] : j["instances_per_mesh"].items()) perMesh += count.get<uint64_t>();
    EXPECT_EQ(perMesh, j["instances"].get<uint64_t>());
    EXPECT_TRUE(j["mesh_notes"].empty()) << j["mesh_notes"];
}

TEST(ExportCli, SceneShapesComeFromGltfFilesWithWarningsForBadOnes) {
    const std::string door = kConfigs + "/../../shared/data/meshes/kenney_platformer_kit/door.glb";
    const std::string scene = ::testing::TempDir() + "export-shapes.json";
    std::ofstream(scene) << R"({"name": "shapes", "seed": 2,
        "grammars": {"residential": {"file": ")" +
                                kConfigs + R"(/grammars/residential.grammar"}},
        "buildings": [{"source": "procedural", "count": 6, "districts": [{"grammar": "residential"}]}],
        "shapes": {"door": {"gltf": ")" +
                                door + R"("}, "chimney": {"gltf": "/nonexistent/chimney.glb"},
                   "unicorn": {"gltf": ")" +
                                door + R"("}}})";
    const std::string out = ::testing::TempDir() + "export-shapes.glb";
    const CommandResult r = runHexlod("export --scene " + scene + " -o " + out + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    std::string notes;
    for (const auto& note : j["mesh_notes"]) notes += note.get<std::string>() + "\n";
    EXPECT_NE(notes.find("/nonexistent/chimney.glb: no such file; using its procedural mesh"),
              std::string::npos)
        << notes;
    EXPECT_NE(notes.find("shapes.unicorn: no grammar of the scene declares this shape"), std::string::npos)
        << notes;
    EXPECT_EQ(notes.find("shape 'door'"), std::string::npos) << notes;
    EXPECT_NE(r.err.find("chimney.glb"), std::string::npos) << "the notes go to stderr too";
    EXPECT_GT(j["instances_per_mesh"]["residential/door"].get<uint64_t>(), 0u);
}

TEST(ExportCli, DispatchesOnTheOutputExtension) {
    const std::string scene = "export --scene " + kConfigs + "/default.json ";
    // .json goes to the scene-config export, which needs the scene's journal (none here).
    const CommandResult json = runHexlod(scene + "-o " + ::testing::TempDir() + "scene.json --journal " +
                                         ::testing::TempDir() + "no-such-journal.jsonl");
    EXPECT_EQ(json.exitCode, 1);
    EXPECT_NE(json.err.find("no edit journal at"), std::string::npos) << json.err;
    const CommandResult obj = runHexlod(scene + "-o " + ::testing::TempDir() + "city.obj");
    EXPECT_EQ(obj.exitCode, 2);
    EXPECT_NE(obj.err.find("must end in .glb, .gltf or .json"), std::string::npos) << obj.err;
}

TEST(ExportCli, BadCellsAndScenesFailWithMessages) {
    const std::string scene =
        "export --scene " + kConfigs + "/default.json -o " + ::testing::TempDir() + "bad.glb ";
    const CommandResult word = runHexlod(scene + "--cells a,b");
    EXPECT_EQ(word.exitCode, 2);
    EXPECT_NE(word.err.find("'a,b' is not a cell"), std::string::npos) << word.err;
    const CommandResult empty = runHexlod(scene + "--cells 9999,9999");
    EXPECT_EQ(empty.exitCode, 2);
    EXPECT_NE(empty.err.find("cell 9999,9999 holds no buildings or trees"), std::string::npos) << empty.err;
    EXPECT_FALSE(std::filesystem::exists(::testing::TempDir() + "bad.glb"));
    const CommandResult missing =
        runHexlod("export --scene /nonexistent/scene.json -o " + ::testing::TempDir() + "x.glb");
    EXPECT_EQ(missing.exitCode, 2);
    EXPECT_NE(missing.err.find("/nonexistent/scene.json"), std::string::npos) << missing.err;
    const CommandResult limit = runHexlod(scene + "--cells=" + firstCell() + " --max-bytes 100000");
    EXPECT_EQ(limit.exitCode, 1);
    EXPECT_NE(limit.err.find("limit of 100000 bytes"), std::string::npos) << limit.err;
}

} // namespace
} // namespace hexlod::test
