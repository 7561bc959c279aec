// The shape asset routes over HTTP with assets attached by hand: the summary's URLs, the
// immutable replies and their 304s, stale keys that name the current URL, and every malformed
// or unknown target. The real assets (meshes from the library, a GL bake) are tested through
// `hexlod serve` in tests/cli/serve_assets_cli_test.cpp.
#include "live_server.h"

#include "hexlod/server/shape_assets.h"

#include <gtest/gtest.h>

namespace hexlod::test {
namespace {

using Json = nlohmann::json;

server::AssetBytes bytes(const std::string& text) {
    return std::make_shared<const std::vector<uint8_t>>(text.begin(), text.end());
}

std::string text(const server::AssetBytes& b) {
    return {b->begin(), b->end()};
}

// Grammar 0: shape 0 has a mesh and an impostor baked without a store (no EXR), shape 1 a
// mesh and a coarse mesh (as a window or a tree part has); grammar 1 has one shape with a mesh and a
// stored impostor; the last grammar has one tree species, baked without a store.
server::ShapeAssets handMadeAssets(const server::SceneService& service) {
    server::ShapeAssets assets;
    const size_t grammars =
        service.withCatalog([](const cells::BatchCatalog& c) { return c.index().grammarCount(); });
    assets.meshes.resize(grammars);
    assets.impostors.resize(grammars);
    assets.meshes[0].push_back(server::MeshAsset{0x1234, bytes("glTF mesh 0"), {3.0f, 2.9f, 0.145f}, {}});
    assets.meshes[0].push_back(server::MeshAsset{0xabcd, bytes("glTF mesh 1"), {1.0f, 1.0f, 0.1f}, {}});
    assets.meshes[0][1]->coarse =
        server::CoarseMeshAsset{0xabce, bytes("coarse glTF mesh 1"), {0.01f, 0.02f, 0.1f}, 28};
    server::ImpostorAsset impostor;
    impostor.key = 0xfeed;
    impostor.centre = {1.5f, 1.45f, 0.0f};
    impostor.radius = 2.0f;
    impostor.boundsMax = {3.0f, 2.9f, 0.1f};
    impostor.albedoPng = bytes("albedo png");
    impostor.normalPng = bytes("normal png");
    assets.impostors[0].push_back(impostor);
    assets.meshes[1].push_back(server::MeshAsset{0x77, bytes("glTF mesh 2"), {1.0f, 1.0f, 1.0f}, {}});
    impostor.key = 0xbeef;
    impostor.layer = 1;
    impostor.exr = bytes("exr file");
    assets.impostors[1].push_back(impostor);
    assets.impostorLayout = {{"sphere", "hemi-octahedral"}, {"grid", 8}};
    server::SpeciesAsset species;
    species.name = "oak";
    species.grammar = uint32_t(grammars - 1);
    species.parameters = {3.8f, 0.7f};
    species.impostor.key = 0x7ee;
    species.impostor.radius = 8.5f;
    species.impostor.albedoPng = bytes("oak albedo");
    species.impostor.normalPng = bytes("oak normal");
    assets.species.push_back(species);
    assets.speciesLayout = {{"sphere", "octahedral"}, {"grid", 8}};
    assets.meshesServed = assets.impostorsServed = assets.speciesServed = true;
    assets.notes = {"terminal meshes (glTF): 3 hand-made meshes"};
    return assets;
}

class ShapeAssetRoutes : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        live = new LiveServer();
        live->service().attachShapeAssets(handMadeAssets(live->service()));
    }
    static void TearDownTestSuite() {
        delete live;
        live = nullptr;
    }
    // `url` answers `body` as an immutable .glb under `etag`, and a conditional GET 304.
    static void expectImmutableGlb(const std::string& url, const std::string& etag, const std::string& body) {
        const auto reply = live->get(url);
        ASSERT_EQ(reply.status, 200) << reply.body;
        EXPECT_EQ(reply.body, body);
        EXPECT_EQ(reply.header("content-type"), "model/gltf-binary");
        EXPECT_EQ(reply.header("etag"), etag);
        EXPECT_EQ(reply.header("cache-control"), "public, max-age=31536000, immutable");
        const auto again = live->get(url, {{"If-None-Match", etag}});
        EXPECT_EQ(again.status, 304);
        EXPECT_TRUE(again.body.empty());
    }
    static LiveServer* live;
};
LiveServer* ShapeAssetRoutes::live = nullptr;

TEST_F(ShapeAssetRoutes, TheSummaryListsEachShapesMeshAndImpostor) {
    const Json s = live->getJson("/api/v1/scene");
    EXPECT_EQ(s["capabilities"]["terminal_meshes"], true);
    EXPECT_EQ(s["capabilities"]["impostors"], true);
    EXPECT_EQ(s["impostor_layout"]["grid"], 8);
    const Json& shapes = s["grammars"][0]["shapes"];
    ASSERT_GE(shapes.size(), 3u);
    EXPECT_EQ(shapes[0]["index"], 0);
    EXPECT_EQ(shapes[0]["mesh_url"], "/api/v1/meshes/0/0/0000000000001234.glb");
    EXPECT_EQ(shapes[0]["nominal_size"], Json({3.0, 2.9, 0.145}));
    const Json& impostor = shapes[0]["impostor"];
    EXPECT_EQ(impostor["albedo_url"], "/api/v1/impostors/0/0/000000000000feed.albedo.png");
    EXPECT_EQ(impostor["normal_url"], "/api/v1/impostors/0/0/000000000000feed.normal.png");
    EXPECT_TRUE(impostor["exr_url"].is_null()); // baked without a store
    EXPECT_EQ(impostor["centre"], Json({1.5, 1.45, 0.0}));
    EXPECT_EQ(impostor["radius"], 2.0);
    EXPECT_EQ(impostor["bounds_max"], Json({3.0, 2.9, 0.1}));
    EXPECT_EQ(impostor["layer"], 0);
    EXPECT_TRUE(shapes[0]["coarse_mesh"].is_null());
    EXPECT_EQ(shapes[1]["mesh_url"], "/api/v1/meshes/0/1/000000000000abcd.glb");
    EXPECT_TRUE(shapes[1]["impostor"].is_null());
    EXPECT_EQ(shapes[1]["coarse_mesh"], Json({{"url", "/api/v1/meshes/0/1/000000000000abce.coarse.glb"},
                                              {"deviation", {0.01, 0.02, 0.1}},
                                              {"triangles", 28}}));
    // A shape without a mesh entry is listed with null URLs and its declared nominal size.
    EXPECT_TRUE(shapes[2]["mesh_url"].is_null());
    EXPECT_EQ(shapes[2]["nominal_size"].size(), 3u);
    EXPECT_EQ(s["grammars"][1]["shapes"][0]["impostor"]["exr_url"],
              "/api/v1/impostors/1/0/000000000000beef.exr");
    bool note = false;
    for (const Json& n : s["notes"]) note = note || n == "terminal meshes (glTF): 3 hand-made meshes";
    EXPECT_TRUE(note);
}

TEST_F(ShapeAssetRoutes, MeshesAreImmutableAndRevalidate) {
    expectImmutableGlb("/api/v1/meshes/0/1/000000000000abcd.glb", "\"000000000000abcd\"", "glTF mesh 1");
}

TEST_F(ShapeAssetRoutes, CoarseMeshesAreServedBesideTheirShapesMesh) {
    expectImmutableGlb("/api/v1/meshes/0/1/000000000000abce.coarse.glb", "\"000000000000abce\"",
                       "coarse glTF mesh 1");
}

TEST_F(ShapeAssetRoutes, ImpostorFilesByKindWithTheirTypes) {
    const auto albedo = live->get("/api/v1/impostors/0/0/000000000000feed.albedo.png");
    ASSERT_EQ(albedo.status, 200);
    EXPECT_EQ(albedo.body, "albedo png");
    EXPECT_EQ(albedo.header("content-type"), "image/png");
    EXPECT_EQ(live->get("/api/v1/impostors/0/0/000000000000feed.normal.png").body, "normal png");
    const auto exr = live->get("/api/v1/impostors/1/0/000000000000beef.exr");
    ASSERT_EQ(exr.status, 200);
    EXPECT_EQ(exr.body, "exr file");
    EXPECT_EQ(exr.header("content-type"), "image/x-exr");
    const auto noExr = live->get("/api/v1/impostors/0/0/000000000000feed.exr");
    EXPECT_EQ(noExr.status, 404);
    EXPECT_NE(noExr.body.find("without a store"), std::string::npos);
}

TEST_F(ShapeAssetRoutes, AStaleKeyNamesTheCurrentUrl) {
    const auto stale = [](const std::string& url, const std::string& current) {
        const auto reply = live->get(url);
        EXPECT_EQ(reply.status, 404) << url;
        EXPECT_EQ(reply.header("x-hexlod-current"), current) << url;
    };
    stale("/api/v1/meshes/0/0/0000000000000001.glb", "/api/v1/meshes/0/0/0000000000001234.glb");
    stale("/api/v1/impostors/0/0/0000000000000001.normal.png",
          "/api/v1/impostors/0/0/000000000000feed.normal.png");
    // A shape's two meshes have a key each: the other one's is stale.
    stale("/api/v1/meshes/0/1/000000000000abcd.coarse.glb", "/api/v1/meshes/0/1/000000000000abce.coarse.glb");
    stale("/api/v1/meshes/0/1/000000000000abce.glb", "/api/v1/meshes/0/1/000000000000abcd.glb");
}

TEST_F(ShapeAssetRoutes, TreeSpeciesAreListedWithTheirExactValuesAndServed) {
    const Json s = live->getJson("/api/v1/scene");
    EXPECT_EQ(s["capabilities"]["tree_billboards"], true);
    EXPECT_EQ(s["tree_impostor_layout"]["sphere"], "octahedral");
    ASSERT_EQ(s["tree_species"].size(), 1u);
    const Json& oak = s["tree_species"][0];
    EXPECT_EQ(oak["name"], "oak");
    EXPECT_EQ(oak["index"], 0);
    EXPECT_EQ(oak["parameters"], Json({3.8, 0.7})) << "shortest decimals of the floats";
    EXPECT_EQ(oak["impostor"]["albedo_url"], "/api/v1/tree-impostors/0/00000000000007ee.albedo.png");
    EXPECT_TRUE(oak["impostor"]["exr_url"].is_null());
    EXPECT_EQ(oak["impostor"]["radius"], 8.5);
    const auto albedo = live->get("/api/v1/tree-impostors/0/00000000000007ee.albedo.png");
    ASSERT_EQ(albedo.status, 200);
    EXPECT_EQ(albedo.body, "oak albedo");
    EXPECT_EQ(albedo.header("content-type"), "image/png");
    EXPECT_EQ(albedo.header("cache-control"), "public, max-age=31536000, immutable");
    EXPECT_EQ(live->get("/api/v1/tree-impostors/0/00000000000007ee.albedo.png",
                        {{"If-None-Match", albedo.header("etag")}})
                  .status,
              304);
    EXPECT_EQ(live->get("/api/v1/tree-impostors/0/00000000000007ee.normal.png").body, "oak normal");
    const auto stale = live->get("/api/v1/tree-impostors/0/0000000000000001.normal.png");
    EXPECT_EQ(stale.status, 404);
    EXPECT_EQ(stale.header("x-hexlod-current"), "/api/v1/tree-impostors/0/00000000000007ee.normal.png");
}

TEST_F(ShapeAssetRoutes, MalformedAndUnknownTargetsSayWhy) {
    const struct {
        const char* target;
        int status;
        const char* reason;
    } cases[] = {
        {"/api/v1/meshes/x/0/0000000000001234.glb", 400, "grammar must be"},
        {"/api/v1/meshes/-1/0/0000000000001234.glb", 400, "grammar must be"},
        {"/api/v1/meshes/0/99999999999/0000000000001234.glb", 400, "shape must be"},
        {"/api/v1/meshes/0/0/1234.glb", 400, "16 hex digits"},
        {"/api/v1/meshes/0/0/000000000000123g.glb", 400, "16 hex digits"},
        {"/api/v1/meshes/0/0/0000000000001234", 400, "16 hex digits"},
        {"/api/v1/meshes/0/0/0000000000001234.gltf", 404, "<key>.glb"},
        {"/api/v1/meshes/0/1/000000000000abce.coarse.gltf", 404, "<key>.coarse.glb"},
        {"/api/v1/meshes/0/0/0000000000001234.coarse.glb", 404, "shape 0 of grammar 0 has no coarse mesh"},
        {"/api/v1/meshes/0/7/0000000000001234.coarse.glb", 404, "declares no shape 7 of grammar 0"},
        {"/api/v1/meshes/0/7/0000000000001234.glb", 404, "declares no shape 7 of grammar 0"},
        {"/api/v1/meshes/99/0/0000000000001234.glb", 404, "declares no shape 0 of grammar 99"},
        {"/api/v1/impostors/0/1/000000000000feed.albedo.png", 404, "has no impostor"},
        {"/api/v1/impostors/0/0/000000000000feed.png", 404, "<key>.albedo.png"},
        {"/api/v1/impostors/0/0/000000000000feed.albedo.png.exr", 404, "<key>.albedo.png"},
        {"/api/v1/meshes/0/0", 404, ""},
        {"/api/v1/tree-impostors/x/00000000000007ee.albedo.png", 400, "species must be"},
        {"/api/v1/tree-impostors/-1/00000000000007ee.albedo.png", 400, "species must be"},
        {"/api/v1/tree-impostors/0/7ee.albedo.png", 400, "16 hex digits"},
        {"/api/v1/tree-impostors/0/00000000000007ee", 400, "16 hex digits"},
        {"/api/v1/tree-impostors/1/00000000000007ee.albedo.png", 404, "there is no species 1"},
        {"/api/v1/tree-impostors/0/00000000000007ee.exr", 404, "without a store"},
        {"/api/v1/tree-impostors/0/00000000000007ee.jpg", 404, "<key>.albedo.png"},
        {"/api/v1/tree-impostors/0", 404, ""},
    };
    for (const auto& c : cases) {
        const auto reply = live->get(c.target);
        EXPECT_EQ(reply.status, c.status) << c.target << ": " << reply.body;
        EXPECT_NE(reply.body.find(c.reason), std::string::npos) << c.target << ": " << reply.body;
    }
}

TEST(ShapeAssets, WithoutAnyTheRoutesSay501AndTheNotesSayWhy) {
    const LiveServer live;
    const auto mesh = live.get("/api/v1/meshes/0/0/0000000000001234.glb");
    EXPECT_EQ(mesh.status, 501);
    EXPECT_NE(mesh.body.find("terminal meshes are not served"), std::string::npos);
    EXPECT_EQ(live.get("/api/v1/impostors/0/0/0000000000001234.exr").status, 501);
    const auto tree = live.get("/api/v1/tree-impostors/0/0000000000001234.albedo.png");
    EXPECT_EQ(tree.status, 501);
    EXPECT_NE(tree.body.find("tree impostors are not served"), std::string::npos);
    const Json s = live.getJson("/api/v1/scene");
    EXPECT_EQ(s["capabilities"]["tree_billboards"], false);
    EXPECT_TRUE(s["tree_species"].empty());
    EXPECT_EQ(s["capabilities"]["terminal_meshes"], false);
    EXPECT_TRUE(s["impostor_layout"].is_null());
    EXPECT_TRUE(s["grammars"][0]["shapes"][0]["mesh_url"].is_null());
}

TEST(ShapeAssets, ByteSizeCountsSharedBytesOnce) {
    server::ShapeAssets assets;
    const server::AssetBytes shared = bytes("0123456789");
    assets.meshes = {{server::MeshAsset{1, shared, {}, {}}}, {server::MeshAsset{1, shared, {}, {}}}};
    const server::AssetBytes coarse = bytes("jk");
    assets.meshes[0][0]->coarse = server::CoarseMeshAsset{2, coarse, {}, 1};
    assets.meshes[1][0]->coarse = server::CoarseMeshAsset{2, coarse, {}, 1}; // shared: counted once
    server::ImpostorAsset impostor;
    impostor.albedoPng = bytes("abc");
    impostor.normalPng = bytes("de");
    assets.impostors = {{impostor}, {std::nullopt}};
    server::SpeciesAsset species;
    species.impostor.albedoPng = bytes("fghi");
    species.impostor.normalPng = impostor.normalPng; // shared: counted once
    assets.species = {species};
    EXPECT_EQ(assets.byteSize(), 21u);
    EXPECT_EQ(text(assets.mesh(1, 0)->glb), "0123456789");
    EXPECT_EQ(assets.mesh(2, 0), nullptr);
    EXPECT_EQ(assets.mesh(0, 1), nullptr);
    EXPECT_EQ(assets.impostor(1, 0), nullptr);
    EXPECT_NE(assets.impostor(0, 0), nullptr);
}

} // namespace
} // namespace hexlod::test
