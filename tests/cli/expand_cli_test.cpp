// `hexlod expand` end to end: help, the JSON contract, and errors on stderr with a
// nonzero exit.
#include "command_runner.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hexlod/grammar/terminal_set_codec.h"

#include <cstdio>
#include <fstream>

namespace hexlod::test {
namespace {

const std::string kConfigs = HEXLOD_CONFIGS_DIR;

TEST(Cli, HelpListsTheCommands) {
    const CommandResult top = runHexlod("--help");
    EXPECT_EQ(top.exitCode, 0);
    EXPECT_NE(top.out.find("expand"), std::string::npos);
    const CommandResult expand = runHexlod("expand --help");
    EXPECT_EQ(expand.exitCode, 0);
    for (const char* option : {"--grammar", "--demo", "--param", "--threads", "--out", "--stats", "--json"}) {
        EXPECT_NE(expand.out.find(option), std::string::npos) << option;
    }
}

TEST(Cli, NoCommandAndUnknownOptionsFail) {
    const CommandResult none = runHexlod("");
    EXPECT_NE(none.exitCode, 0);
    EXPECT_FALSE(none.err.empty());
    const CommandResult unknown =
        runHexlod("expand --grammar " + kConfigs + "/grammars/thesis-example.grammar --bogus");
    EXPECT_NE(unknown.exitCode, 0);
    EXPECT_NE(unknown.err.find("--bogus"), std::string::npos);
}

TEST(Cli, ExpandJsonHasTheDocumentedKeys) {
    const CommandResult r =
        runHexlod("expand --grammar " + kConfigs +
                  "/grammars/thesis-example.grammar --demo 50 --threads 2 --stats --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    for (const char* key : {"buildings", "atoms", "terminals", "bytes", "bytes_per_terminal", "seconds",
                            "terminals_per_second", "threads", "geometry_bytes"}) {
        EXPECT_TRUE(j.contains(key)) << key;
    }
    EXPECT_EQ(j["buildings"], 50);
    EXPECT_EQ(j["threads"], 2);
    EXPECT_GT(j["terminals"].get<uint64_t>(), 1000u);
    EXPECT_GT(j["atoms"].get<uint64_t>(), 150u);
    EXPECT_LE(j["bytes_per_terminal"].get<double>(), 33.0);
    EXPECT_GT(j["geometry_bytes"].get<uint64_t>(), 10 * j["bytes"].get<uint64_t>());
    uint64_t perShape = 0;
    for (const auto& [name, count] : j["terminals_per_shape"].items()) perShape += count.get<uint64_t>();
    EXPECT_EQ(perShape, j["terminals"].get<uint64_t>());
}

TEST(Cli, ParamOverridesAreValidatedByName) {
    const std::string base = "expand --grammar " + kConfigs + "/grammars/thesis-example.grammar --demo 3 ";
    const CommandResult outOfRange = runHexlod(base + "--param floors=1000");
    EXPECT_EQ(outOfRange.exitCode, 2);
    EXPECT_NE(outOfRange.err.find("'floors'"), std::string::npos) << outOfRange.err;
    const CommandResult notANumber = runHexlod(base + "--param floors=nan");
    EXPECT_EQ(notANumber.exitCode, 2);
    EXPECT_NE(notANumber.err.find("floors"), std::string::npos) << notANumber.err;
    const CommandResult unknown = runHexlod(base + "--param storeys=3");
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_NE(unknown.err.find("unknown parameter 'storeys'"), std::string::npos) << unknown.err;
    const CommandResult malformed = runHexlod(base + "--param floors");
    EXPECT_EQ(malformed.exitCode, 2);
    const CommandResult ok = runHexlod(base + "--param floors=10 --json");
    EXPECT_EQ(ok.exitCode, 0) << ok.err;
}

TEST(Cli, GrammarErrorsGoToStderrWithFileLineColumn) {
    const std::string path = ::testing::TempDir() + "broken.grammar";
    std::ofstream(path) << "A -> Extrude(3) { B, NULL };\nB -> Splt(x, 1) { C };\n";
    const CommandResult r = runHexlod("expand --grammar " + path + " --demo 2");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(r.out.empty());
    EXPECT_NE(r.err.find(path + ":2:6: error: unknown rule operation 'Splt'"), std::string::npos) << r.err;
    std::remove(path.c_str());
}

TEST(Cli, OutWritesTheTerminalSet) {
    const std::string path = ::testing::TempDir() + "set.hxt";
    const CommandResult r = runHexlod("expand --grammar " + kConfigs +
                                      "/grammars/thesis-example.grammar --demo 4 --json --out " + path);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    std::ifstream file(path, std::ios::binary);
    ASSERT_TRUE(file);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                                     std::istreambuf_iterator<char>());
    grammar::TerminalSet set;
    std::string error;
    ASSERT_TRUE(grammar::decodeTerminalSet(bytes, set, error)) << error;
    EXPECT_EQ(set.records.size(), j["terminals"].get<uint64_t>());
    EXPECT_LT(bytes.size(), j["bytes"].get<uint64_t>() / 4); // the codec packs 32-byte records tightly
    std::remove(path.c_str());
}

TEST(Cli, UnwritableOutIsAnError) {
    const CommandResult r =
        runHexlod("expand --grammar " + kConfigs +
                  "/grammars/thesis-example.grammar --demo 1 --out /nonexistent/dir/set.bin");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("cannot open"), std::string::npos) << r.err;
}

} // namespace
} // namespace hexlod::test

namespace hexlod::test {
namespace {

TEST(Cli, ExpandSceneReportsEveryBatchAndWhatItLeftOut) {
    const std::string path = ::testing::TempDir() + "small-scene.json";
    std::ofstream(path) << R"({
      "grammars": { "business": { "file": ")" HEXLOD_CONFIGS_DIR R"(/grammars/business.grammar" },
                    "residential": { "file": ")" HEXLOD_CONFIGS_DIR R"(/grammars/residential.grammar" } },
      "buildings": [ { "source": "procedural", "count": 400, "districts": [
          { "grammar": "business", "share": 0.5, "floors": [10, 30] }, { "grammar": "residential" } ] } ] })";
    const CommandResult r = runHexlod("expand --scene " + path + " --threads 2 --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["buildings"], 400);
    EXPECT_EQ(j["trees"], 0);
    EXPECT_EQ(j["batches"].size(), 2u);
    uint64_t terminals = 0;
    for (const auto& batch : j["batches"]) terminals += batch["terminals"].get<uint64_t>();
    EXPECT_EQ(j["terminals"].get<uint64_t>(), terminals);
    EXPECT_GT(terminals, 400u * 100u);
    EXPECT_NE(r.err.find("vegetation: off (no trees)"), std::string::npos) << r.err;
    std::remove(path.c_str());
}

TEST(Cli, BadSceneConfigNamesTheField) {
    const std::string path = ::testing::TempDir() + "bad-scene.json";
    std::ofstream(path)
        << R"({"grammars": {"a": {"file": "x.grammar"}}, "buildings": [], "lod": {"hysteresis": 7}})";
    const CommandResult r = runHexlod("expand --scene " + path);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("lod.hysteresis: must be a finite number in [0, 0.95], got 7"), std::string::npos)
        << r.err;
    const CommandResult both = runHexlod("expand --scene " + path + " --demo 3");
    EXPECT_NE(both.exitCode, 0);
    std::remove(path.c_str());
}

} // namespace
} // namespace hexlod::test
