// Every endpoint of docs/protocol.md against a real server on loopback: status, payload,
// ETag and Cache-Control values, and the 304s.
#include "live_server.h"

#include "hexlod/grammar/extruded_set_codec.h"
#include "hexlod/grammar/terminal_set_codec.h"

#include <gtest/gtest.h>

#include <fstream>
#include <thread>

namespace hexlod::test {
namespace {

using Json = nlohmann::json;

std::span<const uint8_t> bytesOf(const std::string& body) {
    return {reinterpret_cast<const uint8_t*>(body.data()), body.size()};
}

// The first building batch of the index, as the index lists it.
Json firstBuildingBatch(const Json& index, Json* cellOut = nullptr) {
    for (const Json& cell : index["cells"])
        for (const Json& batch : cell["batches"])
            if (batch["grammar"].get<int>() < 2) {
                if (cellOut) *cellOut = cell;
                return batch;
            }
    ADD_FAILURE() << "no building batch";
    return {};
}

// The first building batch's payload of `kind` ("terminal_set" or "extruded_set"), with the
// headers every content response carries checked.
struct Fetched {
    Json cell, batch;
    http_client::Response response;
};
Fetched fetchContent(const LiveServer& live, const std::string& kind, const std::string& contentType) {
    Fetched f;
    f.batch = firstBuildingBatch(live.getJson("/api/v1/cells"), &f.cell);
    f.response = live.get(f.batch[kind]);
    EXPECT_EQ(f.response.status, 200) << f.response.body;
    EXPECT_EQ(f.response.header("content-type"), contentType);
    EXPECT_EQ(f.response.header("etag"), "\"" + f.batch["key"].get<std::string>() + "\"");
    EXPECT_EQ(f.response.header("cache-control"), "public, max-age=31536000, immutable");
    EXPECT_EQ(f.response.header("x-hexlod-version"), "1");
    return f;
}

class Endpoints : public ::testing::Test {
protected:
    static void SetUpTestSuite() { live = new LiveServer(); }
    static void TearDownTestSuite() {
        delete live;
        live = nullptr;
    }
    static LiveServer* live;
};
LiveServer* Endpoints::live = nullptr;

TEST_F(Endpoints, SceneSummaryDescribesGrammarsLodNotesAndCapabilities) {
    const auto response = live->get("/api/v1/scene");
    ASSERT_EQ(response.status, 200);
    EXPECT_EQ(response.header("content-type"), "application/json");
    EXPECT_EQ(response.header("cache-control"), "no-cache");
    EXPECT_EQ(response.header("etag").rfind("W/\"", 0), 0u) << response.header("etag");
    const Json s = Json::parse(response.body);
    EXPECT_EQ(s["name"], "small");
    EXPECT_EQ(s["seed"], 3);
    EXPECT_EQ(s["cell_size"], 60.0);
    EXPECT_EQ(s["counts"]["buildings"], 40);
    EXPECT_EQ(s["counts"]["trees"], 30);
    EXPECT_GT(s["counts"]["cells"].get<int>(), 1);
    ASSERT_GE(s["grammars"].size(), 3u);
    const Json& business = s["grammars"][0];
    EXPECT_EQ(business["name"], "business");
    EXPECT_EQ(business["kind"], "building");
    bool floorHeight = false;
    for (const Json& p : business["parameters"])
        if (p["name"] == "floor_h") {
            floorHeight = true;
            EXPECT_EQ(p["default"], 3.8); // the shortest decimal of the float, not 3.7999999
            EXPECT_LE(p["min"].get<double>(), p["default"].get<double>());
            EXPECT_GE(p["max"].get<double>(), p["default"].get<double>());
        }
    EXPECT_TRUE(floorHeight);
    EXPECT_FALSE(business["shapes"].empty());
    EXPECT_EQ(s["grammars"].back()["kind"], "tree");
    EXPECT_EQ(s["lod"]["max_screen_space_error"], 2.0);
    EXPECT_EQ(s["lod"]["geometric_error"].size(), 5u);
    EXPECT_EQ(s["lod"]["tree_geometric_error"], scene::LodProfile().treeGeometricError);
    EXPECT_EQ(s["capabilities"]["terminal_sets"], true);
    EXPECT_EQ(s["capabilities"]["impostors"], false);
    EXPECT_EQ(s["capabilities"]["edit_auth"], "none");
    EXPECT_EQ(s["formats"]["terminal_set"], 1);
    EXPECT_EQ(s["formats"]["extruded_set"], 1);
    bool impostorNote = false, sceneNote = false;
    for (const Json& note : s["notes"]) {
        impostorNote = impostorNote || note.get<std::string>().find("impostors") == 0;
        sceneNote =
            sceneNote || note.get<std::string>().find("procedural city of 40 buildings") != std::string::npos;
    }
    EXPECT_TRUE(impostorNote);
    EXPECT_TRUE(sceneNote);
    EXPECT_TRUE(s["attributions"].is_array());
    EXPECT_EQ(s["edits"], 0);

    const auto again = live->get("/api/v1/scene", {{"If-None-Match", response.header("etag")}});
    EXPECT_EQ(again.status, 304);
    EXPECT_TRUE(again.body.empty());
}

TEST_F(Endpoints, CellIndexListsOriginsBoundsAndContentUrlsWithTheirKeys) {
    const auto response = live->get("/api/v1/cells");
    ASSERT_EQ(response.status, 200);
    EXPECT_EQ(response.header("cache-control"), "no-cache");
    EXPECT_EQ(response.header("access-control-allow-origin"), "*"); // reads from any origin
    const Json index = Json::parse(response.body);
    size_t buildings = 0, trees = 0, batches = 0;
    for (const Json& cell : index["cells"]) {
        ASSERT_EQ(cell["origin"].size(), 3u);
        for (int i = 0; i < 3; ++i)
            EXPECT_LE(cell["bounds"]["min"][i].get<double>(), cell["bounds"]["max"][i].get<double>());
        buildings += cell["buildings"].get<size_t>();
        trees += cell["trees"].get<size_t>();
        for (const Json& batch : cell["batches"]) {
            ++batches;
            const std::string key = batch["key"];
            EXPECT_EQ(key.size(), 16u);
            EXPECT_EQ(batch["version"], 1);
            const std::string where = std::to_string(cell["q"].get<int>()) + "," +
                                      std::to_string(cell["r"].get<int>()) + "/" +
                                      std::to_string(batch["grammar"].get<int>()) + "/" + key;
            EXPECT_EQ(batch["terminal_set"], "/api/v1/terminal-sets/" + where);
            EXPECT_EQ(batch["extruded_set"], "/api/v1/extruded-sets/" + where);
        }
    }
    EXPECT_EQ(buildings, 40u);
    EXPECT_EQ(trees, 30u);
    EXPECT_EQ(batches, live->getJson("/api/v1/scene")["counts"]["batches"].get<size_t>());
    EXPECT_EQ(live->get("/api/v1/cells", {{"If-None-Match", response.header("etag")}}).status, 304);
    EXPECT_EQ(
        live->get("/api/v1/cells", {{"If-None-Match", "W/\"other\", " + response.header("etag")}}).status,
        304);
    EXPECT_EQ(live->get("/api/v1/cells", {{"If-None-Match", "W/\"other\""}}).status, 200);
}

TEST_F(Endpoints, TerminalSetIsImmutableDecodesAndAnswersConditionalRequests) {
    const auto [cell, batch, response] =
        fetchContent(*live, "terminal_set", "application/vnd.hexlod.terminal-set");
    grammar::TerminalSet set;
    std::string error;
    ASSERT_TRUE(grammar::decodeTerminalSet(bytesOf(response.body), set, error)) << error;
    EXPECT_EQ(set.header.cell.q, cell["q"].get<int>());
    EXPECT_EQ(set.header.cell.r, cell["r"].get<int>());
    EXPECT_EQ(set.header.grammar, batch["grammar"].get<uint32_t>());
    EXPECT_EQ(cache::hexDigest(set.header.key), batch["key"]);
    EXPECT_EQ(set.header.cellOrigin[0], cell["origin"][0].get<double>());
    EXPECT_GT(set.records.size(), 0u);

    const auto notModified = live->get(batch["terminal_set"], {{"If-None-Match", response.header("etag")}});
    EXPECT_EQ(notModified.status, 304);
    EXPECT_TRUE(notModified.body.empty());
    EXPECT_EQ(notModified.header("etag"), response.header("etag"));
    EXPECT_EQ(notModified.header("cache-control"), "public, max-age=31536000, immutable");
    // A second fetch is a payload-cache hit: the very same bytes.
    EXPECT_EQ(live->get(batch["terminal_set"]).body, response.body);
    http_client::Connection connection("127.0.0.1", live->port());
    const auto head = connection.request("HEAD", batch["terminal_set"]);
    EXPECT_EQ(head.status, 200);
    EXPECT_EQ(head.header("content-length"), std::to_string(response.body.size()));
    EXPECT_TRUE(head.body.empty());
}

TEST_F(Endpoints, ExtrudedSetDecodesWithOneBaseVolumePerBuilding) {
    const auto [cell, batch, response] =
        fetchContent(*live, "extruded_set", "application/vnd.hexlod.extruded-set");
    grammar::ExtrudedSetHeader header;
    grammar::ExtrudedSet set;
    std::string error;
    ASSERT_TRUE(grammar::decodeExtrudedSet(bytesOf(response.body), header, set, error)) << error;
    EXPECT_EQ(header.cell.q, cell["q"].get<int>());
    EXPECT_EQ(cache::hexDigest(header.key), batch["key"]);
    EXPECT_EQ(set.buildings.size(), batch["members"].get<size_t>());
    for (const grammar::ExtrudedBuilding& b : set.buildings) {
        EXPECT_GE(b.vertexCount, 3u);
        EXPECT_GT(b.height, 0.0f);
    }
    EXPECT_EQ(live->get(batch["extruded_set"], {{"If-None-Match", response.header("etag")}}).status, 304);
}

TEST_F(Endpoints, BuildingEditsHistoryHealthAndMetrics) {
    const Json building = live->getJson("/api/v1/buildings/5");
    EXPECT_EQ(building["id"], 5);
    EXPECT_TRUE(building["params"].contains("floor_h"));
    EXPECT_TRUE(building["batch"]["terminal_set"].get<std::string>().rfind("/api/v1/terminal-sets/", 0) == 0);
    EXPECT_EQ(live->get("/api/v1/buildings/40").status, 404);

    const Json history = live->getJson("/api/v1/edits");
    EXPECT_TRUE(history["entries"].is_array());
    EXPECT_TRUE(history["undo_next"].is_null());

    const Json health = live->getJson("/healthz");
    EXPECT_EQ(health["status"], "ok");

    // A request is counted once its reply is written, which may be just after the client has
    // read it, and on any of the I/O threads: give each of the last ones a moment.
    http_client::Response metrics;
    for (int attempt = 0; attempt < 50; ++attempt) {
        metrics = live->get("/metrics");
        if (metrics.body.find("route=\"GET /healthz\"") != std::string::npos &&
            metrics.body.find("route=\"GET /api/v1/edits\",status=\"200\"") != std::string::npos)
            break;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ASSERT_EQ(metrics.status, 200);
    EXPECT_EQ(metrics.header("content-type"), "text/plain; version=0.0.4; charset=utf-8");
    for (const char* family :
         {"# TYPE hexlod_http_requests_total counter",
          "# TYPE hexlod_http_request_duration_seconds histogram",
          "hexlod_cache_hits_total{tier=\"terminal_payload\"}",
          "hexlod_cache_evictions_total{tier=\"decoded\"}", "hexlod_cache_bytes{tier=\"extruded_payload\"}",
          "hexlod_generations_total", "hexlod_edits_total", "hexlod_sse_clients",
          "hexlod_http_response_bytes_total", "route=\"GET /api/v1/edits\",status=\"200\"",
          "hexlod_http_request_duration_seconds_bucket{route=\"GET /healthz\",le=\"+Inf\"}"})
        EXPECT_NE(metrics.body.find(family), std::string::npos) << family;
}

TEST_F(Endpoints, UnknownRoutesAndApiVersions404) {
    EXPECT_EQ(live->get("/api/v1/nothing").status, 404);
    const auto v2 = live->get("/api/v2/scene");
    EXPECT_EQ(v2.status, 404);
    EXPECT_NE(v2.body.find("unknown API version"), std::string::npos);
}

TEST_F(Endpoints, WithoutAViewerTheRootIsTheBuiltInPage) {
    const auto page = live->get("/");
    ASSERT_EQ(page.status, 200);
    EXPECT_EQ(page.header("content-type"), "text/html; charset=utf-8");
    EXPECT_NE(page.body.find("web viewer is not built"), std::string::npos);
    EXPECT_NE(page.body.find("/api/v1/cells"), std::string::npos);
    EXPECT_EQ(live->get("/app.js").status, 404);
}

TEST(StaticFilesServed, FromTheWebRootWithContentTypesAndNoEscape) {
    TemporaryFolder outside;
    std::ofstream(outside.file("secret.txt")) << "secret";
    server::ServerOptions options = LiveServer::quietOptions();
    TemporaryFolder web;
    options.webRoot = web.path().string();
    std::filesystem::create_directories(web.path() / "assets");
    std::ofstream(web.file("index.html")) << "<!doctype html><title>viewer</title>";
    std::ofstream((web.path() / "assets" / "app.js").string()) << "console.log(1)";
    std::ofstream((web.path() / "assets" / "style.css").string()) << "body{}";
    std::filesystem::create_symlink(outside.file("secret.txt"), web.path() / "assets" / "link.txt");
    LiveServer live({}, options);

    const auto index = live.get("/");
    ASSERT_EQ(index.status, 200);
    EXPECT_EQ(index.body, "<!doctype html><title>viewer</title>");
    EXPECT_EQ(index.header("content-type"), "text/html; charset=utf-8");
    EXPECT_EQ(index.header("cache-control"), "no-cache");
    EXPECT_EQ(live.get("/", {{"If-None-Match", index.header("etag")}}).status, 304);
    EXPECT_EQ(live.get("/assets/app.js").header("content-type"), "text/javascript; charset=utf-8");
    EXPECT_EQ(live.get("/assets/style.css").header("content-type"), "text/css; charset=utf-8");
    EXPECT_EQ(live.get("/assets/").status, 404); // a folder without index.html
    EXPECT_EQ(live.get("/assets/link.txt").status, 403);
    EXPECT_EQ(live.get("/assets/../../secret.txt").status, 400);
    EXPECT_EQ(live.get("/assets/%2e%2e/%2E%2E/secret.txt").status, 400);
    EXPECT_EQ(live.get("/.hidden").status, 404);
    EXPECT_EQ(live.get("/nothing.png").status, 404);
}

} // namespace
} // namespace hexlod::test
