// The service's bookkeeping of species baked for edits, with a bakery that answers at once
// (the real one, with GL, is tested through `hexlod serve` in tests/cli/serve_assets_cli_test.cpp):
// each new value set is asked for once, a failed bake is announced and never retried, and no
// more than kMaxEditedSpecies are asked for, however many edits come.
#include "live_server.h"

#include "hexlod/server/species_bakery.h"

#include <gtest/gtest.h>

#include <memory>
#include <set>

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
        assets.species.push_back(fakeSpecies({kTreeGrammar, values, "start"}, assets.species.size() + 1));
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

// A service with a species per value set of the start and a bakery that answers at once.
class SpeciesBakes : public ::testing::Test {
protected:
    void start(bool bakesSucceed) {
        started = attachStartSpecies(live);
        live.service().attachSpeciesBakery(std::make_unique<AnsweringBakery>(bakesSucceed, asked));
        events = std::make_unique<http_client::EventStreamReader>("127.0.0.1", live.port(), "/api/v1/events");
        ASSERT_TRUE(events->next(std::chrono::seconds(5))); // hello
    }

    // The next event's name; empty when none comes within 5 s.
    std::string nextKind() {
        const auto event = events->next(std::chrono::seconds(5));
        return event ? event->event : std::string();
    }

    LiveServer live;
    size_t started = 0;
    std::vector<server::SpeciesRequest> asked;
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

TEST_F(SpeciesBakes, NoMoreThanTheCapAreAskedFor) {
    start(true);
    // Every edit gives each species of the park a new value set, until the cap stops the asking.
    for (int edit = 0; asked.size() < server::SceneService::kMaxEditedSpecies && edit < 200; ++edit)
        ASSERT_EQ(live.post("/api/v1/edits", trunkEdit(3.0 + 0.01 * edit)).status, 200);
    EXPECT_EQ(asked.size(), server::SceneService::kMaxEditedSpecies);
    ASSERT_EQ(live.post("/api/v1/edits", trunkEdit(7.77)).status, 200);
    EXPECT_EQ(asked.size(), server::SceneService::kMaxEditedSpecies) << "past the cap, trees stay terminals";
    EXPECT_EQ(live.getJson("/api/v1/scene")["tree_species"].size(),
              started + server::SceneService::kMaxEditedSpecies);
}

} // namespace
} // namespace hexlod::test
