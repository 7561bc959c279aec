// The service's bookkeeping of species baked for edits, with a bakery that answers at once or
// holds its requests as a busy one does (the real one, with GL, is tested through
// `hexlod serve` in tests/cli/serve_assets_cli_test.cpp): each new value set is asked for once,
// a failed bake is announced and never retried, a bake no tree wants by its turn is dropped,
// and no more than kMaxEditedSpecies are held at once, however many edits come: species no
// tree has any more are retired to make room.
#include "live_server.h"

#include "hexlod/server/species_bakery.h"

#include <gtest/gtest.h>

#include <memory>
#include <mutex>
#include <set>
#include <utility>

namespace hexlod::test {
namespace {

using Json = nlohmann::json;

// The tree grammar of the small scene comes after its two building grammars.
constexpr uint32_t kTreeGrammar = 2;

std::string trunkEdit(double value) {
    return R"({"selector":{"grammar":)" + std::to_string(kTreeGrammar) + R"(},"params":{"trunk_h":)" +
           std::to_string(value) + "}}";
}

server::SpeciesAsset fakeSpecies(const server::SpeciesRequest& request, uint64_t key) {
    server::SpeciesAsset asset;
    asset.name = request.name;
    asset.grammar = request.grammar;
    asset.parameters = request.parameters;
    asset.impostor.key = key;
    asset.impostor.albedoPng = std::make_shared<const std::vector<uint8_t>>(std::vector<uint8_t>{1, 2, 3});
    asset.impostor.normalPng = asset.impostor.albedoPng;
    return asset;
}

// The tree value sets as they are now.
std::set<std::vector<float>> valueSets(LiveServer& live) {
    return live.service().withCatalog([](const cells::BatchCatalog& catalog) {
        std::set<std::vector<float>> sets;
        for (const grammar::BuildingInput& tree : catalog.grammar(kTreeGrammar).buildings)
            sets.insert(tree.parameters);
        return sets;
    });
}

// Serves a species per value set of the start, as `hexlod serve` does after its bake.
size_t attachStartSpecies(LiveServer& live) {
    server::ShapeAssets assets;
    for (const std::vector<float>& values : valueSets(live))
        assets.species.push_back(fakeSpecies({kTreeGrammar, values, "start", {}}, assets.species.size() + 1));
    assets.speciesServed = true;
    const size_t count = assets.species.size();
    live.service().attachShapeAssets(std::move(assets));
    return count;
}

class AnsweringBakery : public server::SpeciesBakery {
public:
    AnsweringBakery(bool succeed, std::vector<server::SpeciesRequest>& asked)
        : succeed_(succeed), asked_(asked) {}
    void bake(server::SpeciesRequest request, Done done) override {
        asked_.push_back(request);
        if (!succeed_) return done(std::nullopt, "no GL context to bake it: test");
        done(fakeSpecies(request, 0x1000 + asked_.size()), {});
    }

private:
    bool succeed_;
    std::vector<server::SpeciesRequest>& asked_;
};

// Holds its requests until the test lets them through, as a bakery busy with earlier ones
// does.
class HeldBakery : public server::SpeciesBakery {
public:
    explicit HeldBakery(std::vector<server::SpeciesRequest>& asked) : asked_(asked) {}
    void bake(server::SpeciesRequest request, Done done) override {
        std::lock_guard lock(mutex_);
        asked_.push_back(request);
        held_.emplace_back(std::move(request), std::move(done));
    }
    // Bakes the held requests in order, as the bakery's thread takes them: one no tree wants
    // any more is dropped. Returns how many were baked.
    size_t release() {
        std::vector<std::pair<server::SpeciesRequest, Done>> held;
        {
            std::lock_guard lock(mutex_);
            held.swap(held_);
        }
        size_t baked = 0;
        for (auto& [request, done] : held) {
            if (request.stillWanted && !request.stillWanted()) continue;
            done(fakeSpecies(request, 0x2000 + ++serial_), {});
            ++baked;
        }
        return baked;
    }

private:
    std::mutex mutex_;
    std::vector<server::SpeciesRequest>& asked_;
    std::vector<std::pair<server::SpeciesRequest, Done>> held_;
    uint64_t serial_ = 0;
};

// A service with a species per value set of the start and a bakery that answers at once, or
// one that holds its requests.
class SpeciesBakes : public ::testing::Test {
protected:
    void start(bool bakesSucceed) { start(std::make_unique<AnsweringBakery>(bakesSucceed, asked)); }
    void startHeld() {
        auto bakery = std::make_unique<HeldBakery>(asked);
        held = bakery.get();
        start(std::move(bakery));
    }
    void start(std::unique_ptr<server::SpeciesBakery> bakery) {
        started = attachStartSpecies(live);
        live.service().attachSpeciesBakery(std::move(bakery));
        events = std::make_unique<http_client::EventStreamReader>("127.0.0.1", live.port(), "/api/v1/events");
        ASSERT_TRUE(events->next(std::chrono::seconds(5))); // hello
    }

    // The value of one sample line of /metrics, or -1 when it is missing.
    double metric(const std::string& sample) {
        const std::string text = "\n" + live.get("/metrics").body;
        const size_t at = text.find("\n" + sample + " ");
        return at == std::string::npos ? -1.0 : std::stod(text.substr(at + sample.size() + 2));
    }

    // The next event's name; empty when none comes within 5 s.
    std::string nextKind() {
        const auto event = events->next(std::chrono::seconds(5));
        return event ? event->event : std::string();
    }

    LiveServer live;
    size_t started = 0;
    std::vector<server::SpeciesRequest> asked;
    HeldBakery* held = nullptr; // startHeld's, owned by the service
    std::unique_ptr<http_client::EventStreamReader> events;
};

TEST_F(SpeciesBakes, EachNewValueSetIsAskedForOnceAndServedWhenBaked) {
    start(true);
    ASSERT_EQ(live.post("/api/v1/edits", trunkEdit(4.25)).status, 200);
    const std::set<std::vector<float>> edited = valueSets(live);
    std::set<std::vector<float>> askedSets;
    for (const server::SpeciesRequest& r : asked) askedSets.insert(r.parameters);
    EXPECT_EQ(asked.size(), edited.size());
    EXPECT_EQ(askedSets, edited);
    ASSERT_EQ(nextKind(), "edit");
    for (size_t k = 0; k < edited.size(); ++k) {
        const auto event = events->next(std::chrono::seconds(5));
        ASSERT_TRUE(event);
        EXPECT_EQ(event->event, "species");
        EXPECT_EQ(Json::parse(event->data)["species"]["index"], started + k);
    }
    const Json summary = live.getJson("/api/v1/scene");
    ASSERT_EQ(summary["tree_species"].size(), started + edited.size());
    const std::string url = summary["tree_species"][started]["impostor"]["albedo_url"];
    EXPECT_EQ(live.get(url).status, 200);
    EXPECT_EQ(live.get("/api/v1/tree-impostors/" + std::to_string(started + edited.size()) +
                       "/0000000000000000.albedo.png")
                  .status,
              404);

    // Values served already are not asked for: the undo back to the start's, the same edit again.
    ASSERT_EQ(live.post("/api/v1/edits/undo", "").status, 200);
    ASSERT_EQ(live.post("/api/v1/edits", trunkEdit(4.25)).status, 200);
    EXPECT_EQ(asked.size(), edited.size());
}

TEST_F(SpeciesBakes, AFailedBakeIsAnnouncedAndNotRetried) {
    start(false);
    ASSERT_EQ(live.post("/api/v1/edits", trunkEdit(5.5)).status, 200);
    ASSERT_EQ(nextKind(), "edit");
    const auto failed = events->next(std::chrono::seconds(5));
    ASSERT_TRUE(failed);
    EXPECT_EQ(failed->event, "species-failed");
    EXPECT_NE(Json::parse(failed->data)["error"].get<std::string>().find("no GL context"), std::string::npos);
    const size_t first = asked.size();
    ASSERT_EQ(live.post("/api/v1/edits", trunkEdit(5.5)).status, 200);
    EXPECT_EQ(asked.size(), first);
    EXPECT_EQ(live.getJson("/api/v1/scene")["tree_species"].size(), started) << "nothing added";
    EXPECT_NE(
        live.get("/metrics").body.find("hexlod_tree_species{state=\"failed\"} " + std::to_string(first)),
        std::string::npos);
}

TEST_F(SpeciesBakes, ABakeNoTreeWantsByItsTurnIsDropped) {
    startHeld();
    // A slider released three times while the bakery is busy: only the last values are baked.
    for (const double value : {4.13, 4.67, 5.21})
        ASSERT_EQ(live.post("/api/v1/edits", trunkEdit(value)).status, 200);
    const std::set<std::vector<float>> now = valueSets(live);
    ASSERT_EQ(asked.size(), 3 * now.size());
    EXPECT_EQ(held->release(), now.size());
    for (int e = 0; e < 3; ++e) ASSERT_EQ(nextKind(), "edit");
    std::set<std::vector<float>> served;
    for (size_t k = 0; k < now.size(); ++k) {
        const auto event = events->next(std::chrono::seconds(5));
        ASSERT_TRUE(event);
        ASSERT_EQ(event->event, "species");
        const Json entry = Json::parse(event->data)["species"];
        EXPECT_EQ(entry["index"], started + k) << "the dropped bakes take no index";
        served.insert(live.service().species(entry["index"].get<uint32_t>())->parameters);
    }
    EXPECT_EQ(served, now);
    EXPECT_EQ(metric("hexlod_tree_species_dropped_total"), double(2 * now.size()));
    EXPECT_EQ(metric("hexlod_tree_species{state=\"baking\"}"), 0.0);

    // Dropped values are forgotten, not failed: the undo back to them asks for them again.
    ASSERT_EQ(live.post("/api/v1/edits/undo", "").status, 200);
    EXPECT_EQ(asked.size(), 4 * now.size());
    EXPECT_EQ(held->release(), now.size());
}

TEST_F(SpeciesBakes, NoMoreThanTheCapAreHeldAtOnce) {
    startHeld();
    // Every edit gives each species of the park new values; the bakery takes none of them yet.
    int edits = 0;
    for (; asked.size() < server::SceneService::kMaxEditedSpecies && edits < 200; ++edits)
        ASSERT_EQ(live.post("/api/v1/edits", trunkEdit(3.003 + 0.01 * edits)).status, 200);
    EXPECT_EQ(asked.size(), server::SceneService::kMaxEditedSpecies);
    ASSERT_EQ(live.post("/api/v1/edits", trunkEdit(7.77)).status, 200);
    EXPECT_EQ(asked.size(), server::SceneService::kMaxEditedSpecies)
        << "past the cap, trees stay terminals: a bake under way cannot be retired";
    // Its turn come, every held bake but none is dropped (no tree has those values): room again.
    EXPECT_EQ(held->release(), 0u);
    EXPECT_EQ(metric("hexlod_tree_species_dropped_total"), double(server::SceneService::kMaxEditedSpecies));
    ASSERT_EQ(live.post("/api/v1/edits", trunkEdit(7.79)).status, 200);
    EXPECT_EQ(asked.size(), server::SceneService::kMaxEditedSpecies + valueSets(live).size());
}

TEST_F(SpeciesBakes, AtTheCapSpeciesNoTreeHasAreRetired) {
    start(true);
    // The first edit's species, served; later edits leave no tree with their values.
    ASSERT_EQ(live.post("/api/v1/edits", trunkEdit(3.003)).status, 200);
    const size_t perEdit = asked.size();
    ASSERT_GT(perEdit, 0u);
    const Json first = live.getJson("/api/v1/scene")["tree_species"][started];
    const std::string firstUrl = first["impostor"]["albedo_url"];
    ASSERT_EQ(live.get(firstUrl).status, 200);
    // Far more edits than the cap holds species: each is baked all the same.
    const int edits = int(3 * server::SceneService::kMaxEditedSpecies / perEdit) + 1;
    for (int e = 1; e < edits; ++e)
        ASSERT_EQ(live.post("/api/v1/edits", trunkEdit(3.003 + 0.01 * e)).status, 200);
    EXPECT_EQ(asked.size(), size_t(edits) * perEdit) << "every edit's values were baked";

    const Json listed = live.getJson("/api/v1/scene")["tree_species"];
    EXPECT_LE(listed.size(), started + server::SceneService::kMaxEditedSpecies);
    const std::set<std::vector<float>> now = valueSets(live);
    std::set<std::vector<float>> listedSets;
    for (const Json& entry : listed)
        listedSets.insert(live.service().species(entry["index"].get<uint32_t>())->parameters);
    for (const std::vector<float>& values : now) EXPECT_EQ(listedSets.count(values), 1u) << "in use: kept";
    const double retired = metric("hexlod_tree_species_retired_total");
    EXPECT_EQ(retired + double(listed.size() - started), double(asked.size()));
    // A retired species' files are gone, its index is not taken again.
    const auto gone = live.get(firstUrl);
    EXPECT_EQ(gone.status, 410);
    EXPECT_NE(gone.body.find("retired"), std::string::npos);
    EXPECT_EQ(live.service().speciesCount(), started + asked.size());
}

} // namespace
} // namespace hexlod::test
