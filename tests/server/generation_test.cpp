// Content generation on demand: one expansion per missing batch however many ask at once,
// one expansion for a batch's terminal and extruded sets together, edited buildings spliced
// into their batch, and the bounded queue.
#include "live_server.h"

#include "hexlod/server/generation_pool.h"

#include <gtest/gtest.h>

#include <barrier>
#include <future>
#include <thread>

namespace hexlod::test {
namespace {

using Json = nlohmann::json;

std::vector<Json> buildingBatches(const LiveServer& live) {
    std::vector<Json> out;
    const Json index = live.getJson("/api/v1/cells");
    for (const Json& cell : index["cells"])
        for (const Json& batch : cell["batches"])
            if (batch["grammar"].get<int>() < 2) out.push_back(batch);
    return out;
}

// The service builds no cell nobody asks for: the summary, the index and a building's record
// generate nothing; each content request generates its own batch and no other.
TEST(Generation, OnlyRequestedBatchesAreEverGenerated) {
    LiveServer live;
    live.getJson("/api/v1/scene");
    const std::vector<Json> batches = buildingBatches(live);
    live.getJson("/api/v1/buildings/3");
    EXPECT_EQ(live.service().expansions(), 0u);
    ASSERT_GE(batches.size(), 2u);
    EXPECT_EQ(live.get(batches[1]["terminal_set"]).status, 200);
    EXPECT_EQ(live.service().expansions(), 1u);
    const std::string metrics = live.get("/metrics").body;
    EXPECT_NE(metrics.find("hexlod_generations_total{kind=\"terminal_set\"} 1\n"), std::string::npos);
}

TEST(Generation, ABurstForOneMissingBatchGeneratesItOnce) {
    LiveServer live;
    const Json batch = buildingBatches(live).front();
    constexpr int kClients = 24;
    std::barrier start(kClients);
    std::vector<std::string> bodies(kClients);
    std::vector<int> statuses(kClients);
    std::vector<std::thread> clients;
    for (int i = 0; i < kClients; ++i)
        clients.emplace_back([&, i] {
            http_client::Connection connection("127.0.0.1", live.port());
            start.arrive_and_wait();
            const auto response = connection.get(batch["terminal_set"]);
            statuses[i] = response.status;
            bodies[i] = response.body;
        });
    for (std::thread& t : clients) t.join();
    for (int i = 0; i < kClients; ++i) {
        EXPECT_EQ(statuses[i], 200);
        EXPECT_EQ(bodies[i], bodies[0]);
    }
    EXPECT_EQ(live.service().expansions(), 1u);
    const std::string metrics = live.get("/metrics").body;
    EXPECT_NE(metrics.find("hexlod_generations_total{kind=\"terminal_set\"} 1\n"), std::string::npos)
        << metrics;
    // The same expansion made the extruded set: fetching it expands nothing.
    EXPECT_EQ(live.get(batch["extruded_set"]).status, 200);
    EXPECT_EQ(live.service().expansions(), 1u);
}

TEST(Generation, AnExtrudedSetFirstThenItsTerminalSetCostsOneExpansion) {
    LiveServer live;
    const Json batch = buildingBatches(live).back();
    EXPECT_EQ(live.get(batch["extruded_set"]).status, 200);
    EXPECT_EQ(live.service().expansions(), 1u);
    EXPECT_EQ(live.get(batch["terminal_set"]).status, 200); // decoded tier hit: encoded only
    EXPECT_EQ(live.service().expansions(), 1u);
    const std::string metrics = live.get("/metrics").body;
    EXPECT_NE(metrics.find("hexlod_generations_total{kind=\"terminal_set_encode\"} 1\n"), std::string::npos);
    EXPECT_NE(metrics.find("hexlod_cache_hits_total{tier=\"decoded\"} 1\n"), std::string::npos);
}

// Two buildings of one batch with four or more, by id.
std::vector<int> twoBuildingsOfABatch(const LiveServer& live) {
    for (const Json& batch : buildingBatches(live)) {
        if (batch["members"].get<int>() < 4) continue;
        std::vector<int> ids;
        for (int id = 0; id < 40 && ids.size() < 2; ++id)
            if (live.getJson("/api/v1/buildings/" + std::to_string(id))["batch"]["key"] == batch["key"])
                ids.push_back(id);
        return ids;
    }
    return {};
}

// Edits of buildings whose batch was served expand those buildings alone, spliced into the
// batch's last set (its extruded set too); a service that never saw the batch expands it
// whole, and serves the same bytes.
TEST(Generation, EditedBuildingsAreExpandedAloneAndSplicedIntoTheirBatch) {
    LiveServer live;
    const std::vector<int> ids = twoBuildingsOfABatch(live);
    ASSERT_EQ(ids.size(), 2u);
    const Json batch = live.getJson("/api/v1/buildings/" + std::to_string(ids[0]))["batch"];
    ASSERT_EQ(live.get(batch["terminal_set"]).status, 200);
    ASSERT_EQ(live.get(batch["extruded_set"]).status, 200);
    const std::string edits[] = {
        R"({"selector":{"buildings":[)" + std::to_string(ids[0]) + R"(]},"params":{"floor_h":3.4}})",
        R"({"selector":{"buildings":[)" + std::to_string(ids[1]) + R"(]},"params":{"floors":9}})"};
    for (size_t round = 0; round < 2; ++round) {
        const auto reply = live.post("/api/v1/edits", edits[round]);
        ASSERT_EQ(reply.status, 200) << reply.body;
        const Json change = Json::parse(reply.body)["changed"][0];
        LiveServer fresh; // the edits so far, on a batch it never served
        for (size_t r = 0; r <= round; ++r) ASSERT_EQ(fresh.post("/api/v1/edits", edits[r]).status, 200);
        for (const char* kind : {"terminal_set", "extruded_set"}) {
            const auto spliced = live.get(change[kind]), whole = fresh.get(change[kind]);
            ASSERT_EQ(spliced.status, 200) << kind;
            EXPECT_EQ(spliced.body, whole.body) << kind << " after edit " << round + 1;
        }
        EXPECT_EQ(live.service().expansions(), round + 2); // the batch, then each edit's building
        EXPECT_NE(fresh.get("/metrics").body.find("hexlod_generations_total{kind=\"terminal_set\"} 1\n"),
                  std::string::npos);
    }
    const std::string metrics = live.get("/metrics").body;
    EXPECT_NE(metrics.find("hexlod_generations_total{kind=\"terminal_set_spliced\"} 2\n"), std::string::npos)
        << metrics;
    // An undo goes back to a key served before: nothing expands.
    const auto undo = live.post("/api/v1/edits/undo", "");
    ASSERT_EQ(undo.status, 200) << undo.body;
    EXPECT_EQ(live.get(Json::parse(undo.body)["changed"][0]["terminal_set"]).status, 200);
    EXPECT_EQ(live.service().expansions(), 3u);
}

uint64_t terminalPayloadMisses(const LiveServer& live) {
    const std::string metrics = live.get("/metrics").body;
    const std::string name = "hexlod_cache_misses_total{tier=\"terminal_payload\"} ";
    const size_t at = metrics.find(name);
    return at == std::string::npos ? ~uint64_t(0) : std::stoull(metrics.substr(at + name.size()));
}

// A tier with room for the city and two versions of the edited batch: after six edits, every
// current payload is still cached (with plain LRU the oldest current ones went first).
TEST(Generation, AnEditsOldVersionsAreEvictedBeforeCurrentContent) {
    std::vector<std::string> urls;
    uint64_t total = 0, edited = 0;
    {
        LiveServer probe;
        for (const Json& batch : buildingBatches(probe)) {
            const uint64_t bytes = probe.get(batch["terminal_set"]).body.size();
            total += bytes;
            urls.push_back(batch["terminal_set"]);
        }
        edited = probe.get(probe.getJson("/api/v1/buildings/7")["batch"]["terminal_set"]).body.size();
    }
    server::ServiceOptions options;
    options.terminalPayloadBytes = total + 2 * edited;
    LiveServer live({}, LiveServer::quietOptions(), options);
    for (const std::string& url : urls) ASSERT_EQ(live.get(url).status, 200) << url;
    for (int i = 0; i < 6; ++i) {
        const auto reply =
            live.post("/api/v1/edits", R"({"selector":{"buildings":[7]},"params":{"floor_h":)" +
                                           std::to_string(3.2 + 0.05 * i) + "}}");
        ASSERT_EQ(reply.status, 200) << reply.body;
        ASSERT_EQ(live.get(Json::parse(reply.body)["changed"][0]["terminal_set"]).status, 200);
    }
    const uint64_t misses = terminalPayloadMisses(live);
    for (const Json& batch : buildingBatches(live)) EXPECT_EQ(live.get(batch["terminal_set"]).status, 200);
    EXPECT_EQ(terminalPayloadMisses(live), misses) << "a current payload was evicted";
}

TEST(Generation, EveryBatchOfTheSceneServesBothPayloads) {
    LiveServer live;
    const Json index = live.getJson("/api/v1/cells");
    for (const Json& cell : index["cells"])
        for (const Json& batch : cell["batches"]) {
            EXPECT_EQ(live.get(batch["terminal_set"]).status, 200) << batch.dump();
            EXPECT_EQ(live.get(batch["extruded_set"]).status, 200) << batch.dump();
        }
}

TEST(GenerationPool, DeduplicatesBoundsItsQueueAndAnswersEveryWaiter) {
    server::GenerationPool pool(1, 1);
    std::promise<void> release;
    std::shared_future<void> released = release.get_future().share();
    std::promise<void> runningA;
    std::atomic<int> runsOfA{0}, doneA{0}, doneB{0};
    const auto workA = [&] {
        ++runsOfA;
        runningA.set_value();
        released.wait();
        return server::PayloadOutcome{std::make_shared<const std::vector<uint8_t>>(3, 7), 200, {}, {}};
    };
    using Admission = server::GenerationPool::Admission;
    EXPECT_EQ(pool.submit(1, workA, [&](const server::PayloadOutcome& o) { doneA += o.status == 200; }),
              Admission::Started);
    runningA.get_future().wait(); // A holds the only worker
    EXPECT_EQ(pool.submit(1, workA, [&](const server::PayloadOutcome& o) { doneA += o.bytes->size() == 3; }),
              Admission::Joined);
    const auto workB = [] { return server::PayloadOutcome{nullptr, 500, "b", {}}; };
    EXPECT_EQ(pool.submit(2, workB, [&](const server::PayloadOutcome& o) { doneB += o.status == 503; }),
              Admission::Started);
    EXPECT_EQ(pool.submit(3, workB, [](const server::PayloadOutcome&) { FAIL() << "rejected work ran"; }),
              Admission::Rejected);
    EXPECT_EQ(pool.stats().queued, 1u);
    // stop() cancels the queued B at once, then waits for the running A, released meanwhile.
    std::thread releaser([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        release.set_value();
    });
    pool.stop();
    releaser.join();
    EXPECT_EQ(runsOfA.load(), 1);
    EXPECT_EQ(doneA.load(), 2);
    const server::GenerationPoolStats stats = pool.stats();
    EXPECT_EQ(stats.started, 2u);
    EXPECT_EQ(stats.joined, 1u);
    EXPECT_EQ(stats.rejected, 1u);
    EXPECT_EQ(doneB.load(), 1); // cancelled with 503, never run
}

TEST(GenerationPool, AThrowingJobBecomesA500ForEveryWaiter) {
    server::GenerationPool pool(2, 8);
    std::promise<server::PayloadOutcome> result;
    pool.submit(
        9, []() -> server::PayloadOutcome { throw std::runtime_error("boom"); },
        [&](const server::PayloadOutcome& o) { result.set_value(o); });
    const server::PayloadOutcome outcome = result.get_future().get();
    EXPECT_EQ(outcome.status, 500);
    EXPECT_NE(outcome.error.find("boom"), std::string::npos);
}

} // namespace
} // namespace hexlod::test
