// `hexlod serve` and `hexlod export` as separate processes: every acknowledged edit survives
// kill -9 at a random moment, exactly once, and the torn line a kill can leave is cut away
// at the next start; a bad journal or an unsafe bind refuses to start with a reason.
#include "command_runner.h"
#include "serve_process.h"

#include "../server/live_server.h"

#include "hexlod/server/edit_journal.h"

#include <gtest/gtest.h>

#include <filesystem>

#include <atomic>
#include <csignal>
#include <fstream>
#include <map>
#include <mutex>
#include <random>
#include <set>
#include <sstream>
#include <thread>

namespace hexlod::test {
namespace {

using Json = nlohmann::json;

struct Acknowledged {
    uint64_t seq = 0;
    uint32_t building = 0;
    double floorHeight = 0.0;
};

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// Every entry line of the journal file, parsed (the header skipped).
std::vector<server::JournalEntry> journalEntries(const std::string& path) {
    std::vector<server::JournalEntry> entries;
    std::istringstream lines(readText(path));
    std::string line;
    while (std::getline(lines, line)) {
        server::JournalEntry entry;
        std::string error;
        if (line.find("\"format\":\"hexlod-edit-journal\"") != std::string::npos) continue;
        EXPECT_TRUE(server::EditJournal::parseLine(line, entry, error)) << error << ": " << line;
        entries.push_back(entry);
    }
    return entries;
}

// Journal tests need no impostors: without the bake a start takes well under a second, so a
// test can restart the service many times.
std::vector<std::string> serveArguments(const std::string& scene, const std::string& journal) {
    return {"--scene",       scene, "--port", "0", "--journal", journal, "--web-root", scene + ".no-viewer",
            "--no-impostors"};
}

// Serves `scene` on `journal`, applies `edits` (POST bodies) and stops with SIGTERM.
void serveAndEdit(const std::string& scene, const std::string& journal,
                  const std::vector<std::string>& edits) {
    ServeProcess serve(serveArguments(scene, journal));
    ASSERT_TRUE(serve.waitUntilServing()) << serve.stderrText();
    http_client::Connection connection("127.0.0.1", serve.port());
    for (const std::string& edit : edits)
        ASSERT_EQ(connection.post("/api/v1/edits", edit).status, 200) << edit;
    EXPECT_EQ(serve.stop(SIGTERM), 0);
}

TEST(ServeProcess, EveryAcknowledgedEditSurvivesKill9ExactlyOnce) {
    TemporaryFolder folder;
    const std::string scene = writeSmallScene(folder.path());
    const std::string journal = folder.file("edits.jsonl");
    std::vector<Acknowledged> acknowledged;
    std::mt19937 random(20240611u);
    for (int round = 0; round < 3; ++round) {
        ServeProcess serve(serveArguments(scene, journal));
        ASSERT_TRUE(serve.waitUntilServing()) << serve.stderrText();
        if (round > 0) {
            // The torn line left at the end of the previous round was cut away at start.
            EXPECT_NE(serve.stderrText().find("bytes after the last complete line"), std::string::npos)
                << serve.stderrText();
            EXPECT_EQ(readText(journal).back(), '\n');
        }
        std::atomic<bool> killed{false};
        std::mutex mutex;
        std::vector<std::thread> clients;
        for (int c = 0; c < 2; ++c)
            clients.emplace_back([&, seed = random()] {
                std::mt19937 mine(seed);
                try {
                    http_client::Connection connection("127.0.0.1", serve.port(),
                                                       std::chrono::milliseconds(5000));
                    while (!killed) {
                        const uint32_t building = mine() % 40;
                        const double floorHeight = 3.0 + 0.001 * static_cast<double>(mine() % 1400);
                        const std::string body = R"({"selector":{"buildings":[)" + std::to_string(building) +
                                                 R"(]},"params":{"floor_h":)" + std::to_string(floorHeight) +
                                                 "}}";
                        const auto response = connection.post("/api/v1/edits", body);
                        if (response.status != 200) break; // the server is gone
                        std::lock_guard lock(mutex);
                        acknowledged.push_back({Json::parse(response.body)["seq"].get<uint64_t>(), building,
                                                Json::parse(body)["params"]["floor_h"].get<double>()});
                    }
                } catch (const std::exception&) {
                    // connecting failed after the kill: nothing was acknowledged
                }
            });
        std::this_thread::sleep_for(std::chrono::milliseconds(150 + random() % 400));
        EXPECT_EQ(serve.stop(SIGKILL), 128 + SIGKILL);
        killed = true;
        for (std::thread& t : clients) t.join();

        const std::vector<server::JournalEntry> entries = journalEntries(journal);
        std::map<uint64_t, const server::JournalEntry*> bySeq;
        for (const server::JournalEntry& e : entries) {
            EXPECT_TRUE(bySeq.emplace(e.seq, &e).second) << "seq " << e.seq << " twice";
            if (&e != &entries.front()) {
                EXPECT_EQ(e.seq, (&e - 1)->seq + 1);
            }
        }
        for (const Acknowledged& a : acknowledged) {
            const auto it = bySeq.find(a.seq);
            ASSERT_NE(it, bySeq.end()) << "acknowledged edit " << a.seq << " is not in the journal";
            EXPECT_EQ(it->second->selector["buildings"][0], a.building);
            EXPECT_EQ(it->second->params["floor_h"], a.floorHeight);
        }
        // Each client had at most one edit in flight when a kill came: journaled, never answered.
        EXPECT_LE(entries.size(), acknowledged.size() + 2 * (round + 1));
        // A kill inside an append leaves a torn line; make sure the next start sees one.
        std::ofstream(journal, std::ios::app) << R"({"op":"edit","params":{"floor_h":3.3},"sel)";
    }
    ASSERT_GT(acknowledged.size(), 10u);

    ServeProcess serve(serveArguments(scene, journal));
    ASSERT_TRUE(serve.waitUntilServing()) << serve.stderrText();
    const std::vector<server::JournalEntry> entries = journalEntries(journal);
    http_client::Connection connection("127.0.0.1", serve.port());
    EXPECT_EQ(Json::parse(connection.get("/api/v1/edits?limit=100000").body)["total"], entries.size());
    std::map<uint32_t, double> lastValue; // the journal's last word per building
    for (const server::JournalEntry& e : entries)
        lastValue[e.selector["buildings"][0].get<uint32_t>()] = e.params["floor_h"].get<double>();
    for (const auto& [building, value] : lastValue) {
        const Json state = Json::parse(connection.get("/api/v1/buildings/" + std::to_string(building)).body);
        EXPECT_FLOAT_EQ(state["params"]["floor_h"].get<float>(), static_cast<float>(value)) << building;
    }
    EXPECT_EQ(serve.stop(SIGTERM), 0) << serve.stderrText();
    EXPECT_NE(serve.stderrText().find("stopped"), std::string::npos);
}

TEST(ServeProcess, RefusesToListenBeyondLoopbackWithoutAToken) {
    TemporaryFolder folder;
    const std::string scene = writeSmallScene(folder.path());
    std::vector<std::string> args = serveArguments(scene, folder.file("j.jsonl"));
    args.insert(args.end(), {"--bind", "0.0.0.0"});
    ServeProcess refused(args);
    EXPECT_EQ(refused.wait(), 2);
    EXPECT_NE(refused.stderrText().find("without an edit token"), std::string::npos) << refused.stderrText();
    EXPECT_NE(refused.stderrText().find("HEXLOD_TOKEN"), std::string::npos);

    ServeProcess withToken(args, {"HEXLOD_TOKEN=t0ken"});
    ASSERT_TRUE(withToken.waitUntilServing()) << withToken.stderrText();
    http_client::Connection connection("127.0.0.1", withToken.port());
    const std::string edit = R"({"selector":{"buildings":[1]},"params":{"floor_h":3.2}})";
    EXPECT_EQ(connection.post("/api/v1/edits", edit).status, 401);
    EXPECT_EQ(connection.post("/api/v1/edits", edit, {{"Authorization", "Bearer t0ken"}}).status, 200);
    EXPECT_EQ(withToken.stop(SIGINT), 0);
}

TEST(ServeProcess, ACorruptJournalLineRefusesToStartUnlessRepaired) {
    TemporaryFolder folder;
    const std::string scene = writeSmallScene(folder.path());
    const std::string journal = folder.file("j.jsonl");
    serveAndEdit(scene, journal,
                 {R"({"selector":{"buildings":[2]},"params":{"floor_h":3.1}})",
                  R"({"selector":{"buildings":[2]},"params":{"floor_h":3.2}})",
                  R"({"selector":{"buildings":[2]},"params":{"floor_h":3.3}})"});
    std::string text = readText(journal);
    text[text.find("\"seq\":2") + 6] = '9';
    std::ofstream(journal, std::ios::binary | std::ios::trunc) << text;
    ServeProcess refused(serveArguments(scene, journal));
    EXPECT_EQ(refused.wait(), 1);
    EXPECT_NE(refused.stderrText().find("line 3 is corrupt"), std::string::npos) << refused.stderrText();

    std::vector<std::string> args = serveArguments(scene, journal);
    args.push_back("--journal-repair");
    ServeProcess repaired(args);
    ASSERT_TRUE(repaired.waitUntilServing()) << repaired.stderrText();
    http_client::Connection connection("127.0.0.1", repaired.port());
    EXPECT_EQ(Json::parse(connection.get("/api/v1/edits").body)["total"], 2);
    EXPECT_EQ(repaired.stop(SIGTERM), 0);
}

TEST(ExportCommand, WritesTheEditedSceneOrItsGeometryByTheOutput) {
    TemporaryFolder folder;
    const std::string scene = writeSmallScene(folder.path());
    const std::string journal = folder.file("j.jsonl");
    serveAndEdit(scene, journal, {R"({"selector":{"buildings":[4]},"params":{"floor_h":3.7}})"});
    const std::string out = folder.file("edited.json");
    const CommandResult exported =
        runHexlod("export --scene " + scene + " --journal " + journal + " -o " + out);
    ASSERT_EQ(exported.exitCode, 0) << exported.err;
    EXPECT_NE(exported.out.find("1 edited buildings"), std::string::npos) << exported.out;
    const scene::BuiltScene built = buildSmallScene(out);
    EXPECT_EQ(built.buildingGrammars[0].buildings.size() + built.buildingGrammars[1].buildings.size(), 40u);
    // The same command writes geometry when the output is glTF.
    const CommandResult glb = runHexlod("export --scene " + scene + " -o " + folder.file("city.glb"));
    EXPECT_EQ(glb.exitCode, 0) << glb.err;
    EXPECT_TRUE(std::filesystem::exists(folder.file("city.glb")));
    const CommandResult missing =
        runHexlod("export --scene " + scene + " --journal " + folder.file("none") + " -o " + out);
    EXPECT_EQ(missing.exitCode, 1);
    EXPECT_NE(missing.err.find("no edit journal at"), std::string::npos) << missing.err;
}

} // namespace
} // namespace hexlod::test
