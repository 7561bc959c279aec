// `hexlod cells` and `hexlod import` end to end: the JSON contracts, an imported city that
// builds, and errors on stderr with a nonzero exit.
#include "command_runner.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace hexlod::test {
namespace {

const std::string kConfigs = HEXLOD_CONFIGS_DIR;
const std::string kUtrecht = kConfigs + "/../../shared/data/geojson/utrecht_overture_buildings.geojson";

std::string readFile(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(CellsCli, HelpListsTheNewCommands) {
    const CommandResult top = runHexlod("--help");
    EXPECT_NE(top.out.find("cells"), std::string::npos);
    EXPECT_NE(top.out.find("import"), std::string::npos);
    const CommandResult cells = runHexlod("cells --help");
    EXPECT_EQ(cells.exitCode, 0);
    for (const char* option : {"--scene", "--stats", "--json"})
        EXPECT_NE(cells.out.find(option), std::string::npos);
}

TEST(CellsCli, StatsJsonHasTheKeysAndConsistentNumbers) {
    const CommandResult r = runHexlod("cells --scene " + kConfigs + "/default.json --stats --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    for (const char* key : {"buildings", "trees", "cells", "batches", "seconds", "peak_rss_bytes",
                            "index_bytes", "buildings_per_cell"}) {
        EXPECT_TRUE(j.contains(key)) << key;
    }
    EXPECT_EQ(j["buildings"], 10000);
    EXPECT_EQ(j["trees"], 20000);
    const uint64_t cells = j["cells"], batches = j["batches"];
    EXPECT_GT(cells, 20u);
    EXPECT_GE(batches, cells);
    EXPECT_LE(batches, 3 * cells); // two building grammars and one tree grammar
    EXPECT_GT(j["seconds"].get<double>(), 0.0);
    EXPECT_GT(j["peak_rss_bytes"].get<uint64_t>(), j["index_bytes"].get<uint64_t>());

    const nlohmann::json& d = j["buildings_per_cell"];
    EXPECT_LE(d["cells"].get<uint64_t>(), cells);
    EXPECT_LE(d["min"].get<uint64_t>(), d["median"].get<uint64_t>());
    EXPECT_LE(d["median"].get<uint64_t>(), d["p95"].get<uint64_t>());
    EXPECT_LE(d["p95"].get<uint64_t>(), d["max"].get<uint64_t>());
    EXPECT_NEAR(d["mean"].get<double>() * d["cells"].get<double>(), 10000.0, 1e-6);
    uint64_t histogramCells = 0;
    for (const nlohmann::json& bucket : d["histogram"]) histogramCells += bucket["cells"].get<uint64_t>();
    EXPECT_EQ(histogramCells, d["cells"].get<uint64_t>());
}

TEST(CellsCli, TextModesListCellsOrSummarise) {
    const CommandResult list = runHexlod("cells --scene " + kConfigs + "/default.json");
    ASSERT_EQ(list.exitCode, 0) << list.err;
    EXPECT_NE(list.out.find("z_max"), std::string::npos);
    EXPECT_NE(list.out.find("peak RSS"), std::string::npos);
    const CommandResult stats = runHexlod("cells --scene " + kConfigs + "/default.json --stats");
    ASSERT_EQ(stats.exitCode, 0) << stats.err;
    EXPECT_EQ(stats.out.find("z_max"), std::string::npos);
    EXPECT_NE(stats.out.find("10000 buildings, 20000 trees"), std::string::npos) << stats.out;
}

TEST(CellsCli, BadScenesFailWithMessages) {
    const CommandResult missing = runHexlod("cells --scene /nonexistent/scene.json --stats");
    EXPECT_EQ(missing.exitCode, 2);
    EXPECT_NE(missing.err.find("/nonexistent/scene.json"), std::string::npos) << missing.err;
    const std::string path = ::testing::TempDir() + "cells-bad-grammar.json";
    std::ofstream(path) << R"({"grammars": {"a": {"file": "/nonexistent/a.grammar"}},
        "buildings": [{"source": "procedural", "count": 10, "districts": [{"grammar": "a"}]}]})";
    const CommandResult broken = runHexlod("cells --scene " + path + " --stats");
    EXPECT_EQ(broken.exitCode, 1);
    EXPECT_FALSE(broken.err.empty());
    std::remove(path.c_str());
    EXPECT_NE(runHexlod("cells --stats").exitCode, 0);
}

TEST(ImportCli, UtrechtBecomesASceneThatBuilds) {
    const std::string dir = ::testing::TempDir() + "hexlod-import";
    std::filesystem::create_directories(dir);
    const std::string out = dir + "/utrecht.json";
    const CommandResult r = runHexlod("import " + kUtrecht + " -o " + out + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["buildings"], 3754);
    EXPECT_EQ(j["skipped"], 0);
    EXPECT_EQ(j["grammar"], "residential");

    // Paths are written relative to the config's folder, and nothing else is left behind.
    const nlohmann::json config = nlohmann::json::parse(readFile(out));
    EXPECT_EQ(config["buildings"][0]["source"], "geojson");
    EXPECT_EQ(config["buildings"][0]["grammar"], "residential");
    EXPECT_NE(config["buildings"][0]["path"].get<std::string>().front(), '/');
    EXPECT_NE(config["grammars"]["residential"]["file"].get<std::string>().front(), '/');
    size_t files = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++files;
    EXPECT_EQ(files, 1u);

    const CommandResult cells = runHexlod("cells --scene " + out + " --stats --json");
    ASSERT_EQ(cells.exitCode, 0) << cells.err;
    EXPECT_EQ(nlohmann::json::parse(cells.out)["buildings"], 3754);
    std::filesystem::remove_all(dir);
}

TEST(ImportCli, GrammarByFileAndTextReport) {
    const std::string out = ::testing::TempDir() + "utrecht-business.json";
    const CommandResult r = runHexlod("import " + kUtrecht + " -o " + out + " --grammar " + kConfigs +
                                      "/grammars/business.grammar");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("imported 3754 buildings"), std::string::npos) << r.out;
    const nlohmann::json config = nlohmann::json::parse(readFile(out));
    EXPECT_EQ(config["buildings"][0]["grammar"], "business");
    EXPECT_TRUE(config["grammars"].contains("business"));
    std::remove(out.c_str());
}

TEST(ImportCli, BadInputsFailWithMessages) {
    const std::string out = ::testing::TempDir() + "import-bad.json";
    const CommandResult missing = runHexlod("import /nonexistent/city.geojson -o " + out);
    EXPECT_EQ(missing.exitCode, 2);
    EXPECT_NE(missing.err.find("/nonexistent/city.geojson"), std::string::npos) << missing.err;

    const std::string csv = ::testing::TempDir() + "city.csv";
    std::ofstream(csv) << "x,y\n";
    const CommandResult unknown = runHexlod("import " + csv + " -o " + out);
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_NE(unknown.err.find("unknown footprint format"), std::string::npos) << unknown.err;
    std::remove(csv.c_str());

    const std::string notJson = ::testing::TempDir() + "broken.geojson";
    std::ofstream(notJson) << "{ not json";
    const CommandResult broken = runHexlod("import " + notJson + " -o " + out);
    EXPECT_EQ(broken.exitCode, 1);
    EXPECT_FALSE(broken.err.empty());
    std::remove(notJson.c_str());

    const CommandResult unwritable = runHexlod("import " + kUtrecht + " -o /nonexistent/dir/scene.json");
    EXPECT_EQ(unwritable.exitCode, 1);
    EXPECT_NE(unwritable.err.find("cannot write '/nonexistent/dir/scene.json'"), std::string::npos)
        << unwritable.err;

    const CommandResult grammar = runHexlod("import " + kUtrecht + " -o " + out + " --grammar no_such_style");
    EXPECT_EQ(grammar.exitCode, 2);
    EXPECT_NE(grammar.err.find("no_such_style"), std::string::npos) << grammar.err;
    EXPECT_FALSE(std::filesystem::exists(out));

    EXPECT_NE(runHexlod("import " + kUtrecht).exitCode, 0); // -o is required
}

} // namespace
} // namespace hexlod::test

namespace hexlod::test {
namespace {

TEST(CellsCli, GenerateReportsTimeAndBytesPerCell) {
    const CommandResult r = runHexlod("cells --scene " + std::string(HEXLOD_CONFIGS_DIR) +
                                      "/default.json --generate --cells 3 --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    const nlohmann::json& g = j.at("generation");
    EXPECT_EQ(g["cells_generated"], 3);
    for (const char* key :
         {"milliseconds_per_cell", "bytes_per_cell", "encoded_bytes_per_cell", "terminals_per_cell",
          "building_bytes_per_cell", "building_encoded_bytes_per_cell"}) {
        const nlohmann::json& v = g.at(key);
        EXPECT_LE(v["median"].get<double>(), v["p95"].get<double>()) << key;
        EXPECT_LE(v["p95"].get<double>(), v["max"].get<double>()) << key;
    }
    // Records are 32 bytes and the codec packs them several times smaller.
    EXPECT_GT(g["bytes_per_cell"]["max"].get<double>(),
              32.0 * g["terminals_per_cell"]["max"].get<double>() - 1.0);
    EXPECT_LT(g["encoded_bytes_per_cell"]["max"].get<double>(), g["bytes_per_cell"]["max"].get<double>());
}

} // namespace
} // namespace hexlod::test
