// Edits over HTTP: concurrent clients, the journal holding each acknowledged edit exactly
// once, final parameters equal to a serial replay, undo, change events, and the edit token.
#include "live_server.h"

#include "hexlod/cells/batch_catalog.h"
#include "hexlod/server/edit_journal.h"

#include <gtest/gtest.h>

#include <fstream>
#include <mutex>
#include <random>
#include <set>
#include <thread>

namespace hexlod::test {
namespace {

using Json = nlohmann::json;

std::vector<server::JournalEntry> readJournal(const std::string& path) {
    std::vector<server::JournalEntry> entries;
    std::vector<std::string> notes;
    std::string error;
    server::JournalOpenOptions options;
    options.readOnly = true;
    EXPECT_TRUE(server::EditJournal::open(path, options, entries, notes, error)) << error;
    return entries;
}

// Every building's and tree's parameter vector.
std::vector<std::vector<float>> allParameters(const cells::BatchCatalog& catalog) {
    std::vector<std::vector<float>> out;
    for (uint32_t g = 0; g < catalog.index().grammarCount(); ++g)
        for (const grammar::BuildingInput& b : catalog.grammar(g).buildings) out.push_back(b.parameters);
    return out;
}

TEST(Edits, AnEditChangesExactlyItsBatchAndTheOldUrlPointsToTheNewOne) {
    LiveServer live;
    const Json building = live.getJson("/api/v1/buildings/7");
    const std::string before = building["batch"]["terminal_set"];
    const auto response =
        live.post("/api/v1/edits", R"({"selector":{"buildings":[7]},"params":{"floor_h":3.1},
                                                         "comment":"lower storeys"})");
    ASSERT_EQ(response.status, 200) << response.body;
    EXPECT_EQ(response.header("cache-control"), "no-store");
    EXPECT_EQ(response.header("access-control-allow-origin"), ""); // writes only from the same origin
    const Json reply = Json::parse(response.body);
    EXPECT_EQ(reply["seq"], 1);
    EXPECT_EQ(reply["op"], "edit");
    ASSERT_EQ(reply["changed"].size(), 1u);
    const Json& change = reply["changed"][0];
    EXPECT_EQ(change["version"], 2);
    EXPECT_EQ(change["cell"], building["cell"]);
    EXPECT_EQ("/api/v1/terminal-sets/" + std::to_string(change["cell"][0].get<int>()) + "," +
                  std::to_string(change["cell"][1].get<int>()) + "/" +
                  std::to_string(change["grammar"].get<int>()) + "/" + change["key"].get<std::string>(),
              change["terminal_set"]);
    EXPECT_NE(change["terminal_set"], before);
    EXPECT_EQ(change["previous_terminal_set"], before);

    const auto stale = live.get(before);
    EXPECT_EQ(stale.status, 404);
    EXPECT_EQ(stale.header("x-hexlod-current"), change["terminal_set"]);
    EXPECT_EQ(live.get(change["terminal_set"]).status, 200);
    EXPECT_EQ(live.getJson("/api/v1/buildings/7")["params"]["floor_h"], 3.1);
    const Json history = live.getJson("/api/v1/edits");
    ASSERT_EQ(history["entries"].size(), 1u);
    EXPECT_EQ(history["entries"][0]["comment"], "lower storeys");
    EXPECT_EQ(history["undo_next"], 1);
    EXPECT_EQ(live.getJson("/api/v1/scene")["edits"], 1);

    // Undo brings the old key, and so the old URL, back with a new version.
    const auto undo = live.post("/api/v1/edits/undo", "");
    ASSERT_EQ(undo.status, 200) << undo.body;
    const Json undone = Json::parse(undo.body);
    EXPECT_EQ(undone["undoes"], 1);
    EXPECT_EQ(undone["changed"][0]["terminal_set"], before);
    EXPECT_EQ(undone["changed"][0]["version"], 3);
    EXPECT_EQ(live.get(before).status, 200);
    EXPECT_EQ(live.post("/api/v1/edits/undo", "{}").status, 409);
    const Json after = live.getJson("/api/v1/edits");
    EXPECT_EQ(after["entries"][0]["status"], "undone");
    EXPECT_EQ(after["entries"][0]["undone_by"], 2);
}

TEST(Edits, GrammarAndCellSelectorsRekeyEveryBatchTheyTouch) {
    LiveServer live;
    const auto grammarEdit =
        live.post("/api/v1/edits", R"({"selector":{"grammar":"residential"},"params":{"floor_h":3.1}})");
    ASSERT_EQ(grammarEdit.status, 200) << grammarEdit.body;
    size_t residentialBatches = 0;
    const Json index = live.getJson("/api/v1/cells");
    for (const Json& cell : index["cells"])
        for (const Json& batch : cell["batches"]) residentialBatches += batch["grammar"] == 1;
    EXPECT_EQ(Json::parse(grammarEdit.body)["changed"].size(), residentialBatches);

    const Json cell = index["cells"][2];
    const std::string body = R"({"selector":{"cell":[)" + std::to_string(cell["q"].get<int>()) + "," +
                             std::to_string(cell["r"].get<int>()) + R"(]},"params":{"floor_h":3.5}})";
    const auto cellEdit = live.post("/api/v1/edits", body);
    ASSERT_EQ(cellEdit.status, 200) << cellEdit.body;
    const Json cellReply = Json::parse(cellEdit.body);
    for (const Json& change : cellReply["changed"]) EXPECT_EQ(change["cell"][0], cell["q"]);
}

TEST(Edits, ConcurrentClientsLoseNothingAndTheJournalReplaysToTheSameState) {
    LiveServer live;
    constexpr int kClients = 6, kEditsEach = 15;
    std::mutex mutex;
    std::vector<uint64_t> acknowledged;
    std::vector<std::thread> clients;
    for (int c = 0; c < kClients; ++c)
        clients.emplace_back([&, c] {
            std::mt19937 random(static_cast<unsigned>(c) * 7919u + 1u);
            http_client::Connection connection("127.0.0.1", live.port());
            for (int i = 0; i < kEditsEach; ++i) {
                const int building = static_cast<int>(random() % 40);
                const double floorHeight = 3.0 + 0.01 * static_cast<double>(random() % 150);
                const std::string body = R"({"selector":{"buildings":[)" + std::to_string(building) +
                                         R"(]},"params":{"floor_h":)" + std::to_string(floorHeight) + "}}";
                const auto response = i % 5 == 4 ? connection.post("/api/v1/edits/undo", "")
                                                 : connection.post("/api/v1/edits", body);
                if (response.status == 409) continue; // nothing left to undo: legitimate
                ASSERT_EQ(response.status, 200) << response.body;
                std::lock_guard lock(mutex);
                acknowledged.push_back(Json::parse(response.body)["seq"].get<uint64_t>());
            }
        });
    for (std::thread& t : clients) t.join();

    const std::vector<server::JournalEntry> entries = readJournal(live.journalPath());
    std::multiset<uint64_t> journaled;
    for (const server::JournalEntry& e : entries) journaled.insert(e.seq);
    EXPECT_EQ(journaled.size(), acknowledged.size());
    for (const uint64_t seq : acknowledged) EXPECT_EQ(journaled.count(seq), 1u) << seq;
    for (size_t i = 0; i < entries.size(); ++i) EXPECT_EQ(entries[i].seq, i + 1);

    // A serial replay of the journal on a fresh catalog gives the server's parameters.
    cells::BatchCatalog serial(buildSmallScene(live.scenePath()));
    for (const server::JournalEntry& e : entries) {
        if (e.op == server::JournalEntry::Op::Undo) {
            ASSERT_TRUE(serial.undo().ok);
            continue;
        }
        server::EditSpec spec;
        server::EditError error;
        ASSERT_TRUE(server::editFromJson(e.selector, e.params, spec, error)) << error.text();
        ASSERT_TRUE(serial.setParams(spec.selector, spec.params).ok);
    }
    const auto live_ =
        live.service().withCatalog([](const cells::BatchCatalog& c) { return allParameters(c); });
    EXPECT_EQ(live_, allParameters(serial));

    // And the server itself replays to the same state after a restart.
    live.restart();
    EXPECT_EQ(live.service().withCatalog([](const cells::BatchCatalog& c) { return allParameters(c); }),
              live_);
    EXPECT_EQ(live.service().lastSeq(), entries.size());
}

TEST(Edits, SubscribersSeeEveryEditWithItsNewVersionsAndUrls) {
    LiveServer live;
    http_client::EventStreamReader first("127.0.0.1", live.port(), "/api/v1/events");
    http_client::EventStreamReader second("127.0.0.1", live.port(), "/api/v1/events");
    ASSERT_EQ(first.status(), 200);
    EXPECT_EQ(first.header("content-type"), "text/event-stream; charset=utf-8");
    EXPECT_EQ(first.header("cache-control"), "no-store");
    const auto hello = first.next(std::chrono::seconds(5));
    ASSERT_TRUE(hello);
    EXPECT_EQ(hello->event, "hello");
    EXPECT_EQ(Json::parse(hello->data)["seq"], 0);
    ASSERT_TRUE(second.next(std::chrono::seconds(5)));

    const auto response =
        live.post("/api/v1/edits", R"({"selector":{"buildings":[3]},"params":{"floor_h":3.3}})");
    ASSERT_EQ(response.status, 200);
    const Json reply = Json::parse(response.body);
    for (http_client::EventStreamReader* reader : {&first, &second}) {
        const auto event = reader->next(std::chrono::seconds(5));
        ASSERT_TRUE(event);
        EXPECT_EQ(event->event, "edit");
        EXPECT_EQ(event->id, "1");
        const Json data = Json::parse(event->data);
        EXPECT_EQ(data["changed"], reply["changed"]);
        EXPECT_EQ(data["changed"][0]["version"], 2);
        EXPECT_EQ(data["cells"].size(), 1u);
    }
    // Heartbeats are comments: the next event is the undo, not a heartbeat.
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    ASSERT_EQ(live.post("/api/v1/edits/undo", "").status, 200);
    const auto undo = first.next(std::chrono::seconds(5));
    ASSERT_TRUE(undo);
    EXPECT_EQ(undo->event, "undo");
    EXPECT_EQ(undo->id, "2");

    // A reconnecting client gets what it missed after its Last-Event-ID.
    http_client::EventStreamReader resumed("127.0.0.1", live.port(), "/api/v1/events",
                                           {{"Last-Event-ID", "1"}});
    ASSERT_EQ(resumed.next(std::chrono::seconds(5))->event, "hello");
    const auto missed = resumed.next(std::chrono::seconds(5));
    ASSERT_TRUE(missed);
    EXPECT_EQ(missed->id, "2");
}

TEST(Edits, ASlowSubscriberIsDroppedAndNeverHoldsUpEdits) {
    server::ServerOptions options = LiveServer::quietOptions();
    options.eventQueueFrames = 4;
    LiveServer live({}, options);
    http_client::EventStreamReader slow("127.0.0.1", live.port(), "/api/v1/events", {}, 4096);
    ASSERT_EQ(slow.status(), 200);
    slow.close(); // reads no more: frames fill the socket buffers, then its queue
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < 200; ++i) {
        const std::string body = R"({"selector":{"grammar":"residential"},"params":{"floor_h":)" +
                                 std::to_string(3.0 + 0.005 * i) + "}}";
        ASSERT_EQ(live.post("/api/v1/edits", body).status, 200);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 60.0); // hang detection only: each edit costs an fsync, never a wait on the reader
    const std::string metrics = live.get("/metrics").body;
    EXPECT_NE(metrics.find("hexlod_sse_dropped_total 1"), std::string::npos);
}

TEST(Edits, WithATokenEditsNeedTheBearerHeader) {
    server::ServerOptions options = LiveServer::quietOptions();
    options.token = "s3cret";
    server::ServiceOptions service;
    service.editsNeedToken = true;
    LiveServer live({}, options, service);
    const std::string body = R"({"selector":{"buildings":[1]},"params":{"floor_h":3.2}})";
    const auto missing = live.post("/api/v1/edits", body);
    EXPECT_EQ(missing.status, 401);
    EXPECT_EQ(missing.header("www-authenticate"), "Bearer realm=\"hexlod\"");
    EXPECT_EQ(live.post("/api/v1/edits", body, {{"Authorization", "Bearer wrong"}}).status, 403);
    EXPECT_EQ(live.post("/api/v1/edits", body, {{"Authorization", "Basic czNjcmV0"}}).status, 403);
    EXPECT_EQ(live.post("/api/v1/edits/undo", "").status, 401);
    EXPECT_EQ(live.post("/api/v1/edits", body, {{"Authorization", "Bearer s3cret"}}).status, 200);
    EXPECT_EQ(live.getJson("/api/v1/scene")["capabilities"]["edit_auth"], "bearer");
    EXPECT_EQ(live.get("/api/v1/cells").status, 200); // reading needs no token
    EXPECT_EQ(readJournal(live.journalPath()).size(), 1u);
}

TEST(BindPolicy, NonLoopbackAddressesNeedAToken) {
    server::ServerOptions options;
    std::string error;
    options.bind = "127.0.0.1";
    EXPECT_TRUE(server::checkBindPolicy(options, error));
    options.bind = "::1";
    EXPECT_TRUE(server::checkBindPolicy(options, error));
    options.bind = "127.8.9.10";
    EXPECT_TRUE(server::checkBindPolicy(options, error));
    options.bind = "0.0.0.0";
    EXPECT_FALSE(server::checkBindPolicy(options, error));
    EXPECT_NE(error.find("--token"), std::string::npos) << error;
    options.bind = "192.168.1.20";
    EXPECT_FALSE(server::checkBindPolicy(options, error));
    options.token = "t";
    EXPECT_TRUE(server::checkBindPolicy(options, error));
}

} // namespace
} // namespace hexlod::test
