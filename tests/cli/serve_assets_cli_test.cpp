// `hexlod serve`'s shape assets as a client sees them, from a real process with a real GL bake
// (llvmpipe here): a .glb for every declared shape that decodes to the library's mesh, an
// impostor for exactly the shapes the scene's buildings emit and for nothing else, one for each
// tree species with trees, PNGs of the atlas's size that agree with the EXR the store holds, and
// a store reused on the next start.
// Without GL (--no-impostors) the meshes are still served and the notes say why impostors are not.
// An edit that gives trees new values makes the running service bake species for them.
#include "serve_process.h"

#include "../server/live_server.h"

#include "hexlod/grammar/rule_reachability.h"
#include "hexlod/impostor/impostor_store.h"
#include "hexlod/render/mesh_deviation.h"
#include "hexlod/render/procedural_meshes.h"
#include "hexlod/render/terminal_mesh_library.h"

#include <gtest/gtest.h>
#include <stb_image.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <fstream>
#include <map>
#include <set>

namespace hexlod::test {
namespace {

using Json = nlohmann::json;

std::vector<std::string> baseArguments(const TemporaryFolder& folder, const std::string& scene,
                                       const std::string& journal = "edits.jsonl") {
    return {"--scene",    scene,
            "--port",     "0",
            "--journal",  folder.file(journal),
            "--web-root", folder.file("no-viewer")};
}

// Small impostors, so the bake on a software GL stays short.
std::vector<std::string> serveArguments(const TemporaryFolder& folder, const std::string& scene,
                                        const std::string& journal = "edits.jsonl") {
    std::vector<std::string> args = baseArguments(folder, scene, journal);
    for (const char* a : {"--impostor-grid", "4", "--impostor-res", "16", "--impostor-store"})
        args.push_back(a);
    args.push_back(folder.file("store"));
    return args;
}

// A park of 30 trees of the shipped species, and no building.
std::string writeTreesOnlyScene(const TemporaryFolder& folder) {
    SmallScene trees;
    trees.buildings = 0;
    trees.trees = 30;
    return writeSmallScene(folder.path(), trees);
}

struct DecodedPng {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
};

DecodedPng decodePng(const std::string& body) {
    DecodedPng out;
    int channels = 0;
    unsigned char* pixels = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(body.data()),
                                                  int(body.size()), &out.width, &out.height, &channels, 4);
    EXPECT_NE(pixels, nullptr) << stbi_failure_reason();
    if (!pixels) return out;
    out.rgba.assign(pixels, pixels + size_t(out.width) * out.height * 4);
    stbi_image_free(pixels);
    return out;
}

std::string note(const Json& summary, const std::string& prefix) {
    for (const Json& n : summary["notes"])
        if (n.get<std::string>().rfind(prefix, 0) == 0) return n;
    return {};
}

class ServeAssets : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        folder = new TemporaryFolder();
        scenePath = new std::string(writeSmallScene(folder->path()));
        serve = new ServeProcess(serveArguments(*folder, *scenePath));
        // The first start bakes every emitted shape on a software GL.
        ASSERT_TRUE(serve->waitUntilServing(std::chrono::seconds(240))) << serve->stderrText();
        connection = new http_client::Connection("127.0.0.1", serve->port());
        const auto reply = connection->get("/api/v1/scene");
        ASSERT_EQ(reply.status, 200);
        summary = new Json(Json::parse(reply.body));
        built = new scene::BuiltScene(buildSmallScene(*scenePath));
    }
    static void TearDownTestSuite() {
        delete connection;
        if (serve) {
            EXPECT_EQ(serve->stop(SIGTERM), 0);
        }
        delete serve;
        delete summary;
        delete built;
        delete scenePath;
        delete folder;
    }
    // GET `url` as a .glb and parse it.
    static ::testing::AssertionResult fetchGlb(const std::string& url, tinygltf::Model& model) {
        const auto reply = connection->get(url);
        if (reply.status != 200) return ::testing::AssertionFailure() << url << ": " << reply.status;
        if (reply.header("content-type") != "model/gltf-binary")
            return ::testing::AssertionFailure() << url << ": " << reply.header("content-type");
        tinygltf::TinyGLTF loader;
        std::string err, warn;
        if (!loader.LoadBinaryFromMemory(&model, &err, &warn,
                                         reinterpret_cast<const unsigned char*>(reply.body.data()),
                                         unsigned(reply.body.size())))
            return ::testing::AssertionFailure() << url << ": " << err;
        return ::testing::AssertionSuccess();
    }
    static const grammar::CompiledGrammar& grammarAt(size_t g) {
        const size_t buildings = built->buildingGrammars.size();
        return g < buildings ? built->buildingGrammars[g].grammar
                             : built->treeGrammars[g - buildings].grammar;
    }

    static TemporaryFolder* folder;
    static std::string* scenePath;
    static ServeProcess* serve;
    static http_client::Connection* connection;
    static Json* summary;
    static scene::BuiltScene* built;
};
TemporaryFolder* ServeAssets::folder = nullptr;
std::string* ServeAssets::scenePath = nullptr;
ServeProcess* ServeAssets::serve = nullptr;
http_client::Connection* ServeAssets::connection = nullptr;
Json* ServeAssets::summary = nullptr;
scene::BuiltScene* ServeAssets::built = nullptr;

TEST_F(ServeAssets, ImpostorsForExactlyTheEmittedFacadeShapes) {
    ASSERT_EQ((*summary)["capabilities"]["impostors"], true) << serve->stderrText();
    EXPECT_EQ((*summary)["capabilities"]["terminal_meshes"], true);
    const Json& grammars = (*summary)["grammars"];
    size_t impostors = 0, declared = 0;
    std::set<uint32_t> layers;
    for (size_t g = 0; g < grammars.size(); ++g) {
        const bool tree = grammars[g]["kind"] == "tree";
        const std::vector<bool> emitted = grammar::emittedShapes(grammarAt(g));
        ASSERT_EQ(grammars[g]["shapes"].size(), emitted.size());
        for (size_t s = 0; s < emitted.size(); ++s) {
            const Json& shape = grammars[g]["shapes"][s];
            ++declared;
            EXPECT_TRUE(shape["mesh_url"].is_string()) << shape["name"];
            const bool expected = !tree && emitted[s];
            EXPECT_EQ(!shape["impostor"].is_null(), expected) << grammars[g]["name"] << "/" << shape["name"];
            if (shape["impostor"].is_null()) continue;
            ++impostors;
            layers.insert(shape["impostor"]["layer"].get<uint32_t>());
            EXPECT_GT(shape["impostor"]["radius"].get<double>(), 0.0);
        }
    }
    EXPECT_GT(impostors, 0u);
    EXPECT_LT(impostors, declared); // the grammars declare shapes this scene never emits
    EXPECT_EQ(*layers.rbegin() + 1, layers.size()) << "layers are 0..n-1";
    EXPECT_NE(note(*summary, "impostors (EXR, PNG): facade shapes and "), "");
}

// One full-sphere impostor per species that has trees, keyed by the species' exact parameter
// values: every tree of the scene finds its own, and nothing else is served.
TEST_F(ServeAssets, EveryTreeFindsItsSpeciesImpostor) {
    ASSERT_EQ((*summary)["capabilities"]["tree_billboards"], true) << serve->stderrText();
    const Json& layout = (*summary)["tree_impostor_layout"];
    EXPECT_EQ(layout["sphere"], "octahedral");
    EXPECT_EQ(layout["grid"], 4);
    EXPECT_EQ(layout["view_resolution"], 32); // twice the facades' texels
    const Json& species = (*summary)["tree_species"];
    std::map<std::pair<uint32_t, std::vector<float>>, size_t> byValues;
    for (size_t s = 0; s < species.size(); ++s) {
        EXPECT_EQ(species[s]["index"], s);
        std::vector<float> values;
        for (const Json& v : species[s]["parameters"]) values.push_back(v.get<float>());
        EXPECT_TRUE(byValues.emplace(std::pair{species[s]["grammar"].get<uint32_t>(), values}, s).second)
            << "two species with the same values";
        EXPECT_EQ((*summary)["grammars"][species[s]["grammar"].get<size_t>()]["kind"], "tree");
    }
    std::set<size_t> used;
    const uint32_t buildingGrammars = uint32_t(built->buildingGrammars.size());
    for (uint32_t t = 0; t < built->treeGrammars.size(); ++t)
        for (const grammar::BuildingInput& tree : built->treeGrammars[t].buildings) {
            const auto found = byValues.find({buildingGrammars + t, tree.parameters});
            ASSERT_NE(found, byValues.end()) << "tree " << tree.id << " has no species impostor";
            used.insert(found->second);
        }
    EXPECT_EQ(used.size(), species.size()) << "a species without trees was served";

    const Json& impostor = species[0]["impostor"];
    const auto albedo = connection->get(impostor["albedo_url"]);
    ASSERT_EQ(albedo.status, 200) << albedo.body;
    EXPECT_EQ(albedo.header("content-type"), "image/png");
    EXPECT_EQ(albedo.header("cache-control"), "public, max-age=31536000, immutable");
    const DecodedPng a = decodePng(albedo.body);
    EXPECT_EQ(a.width, layout["atlas_size"].get<int>());
    size_t covered = 0;
    for (size_t i = 3; i < a.rgba.size(); i += 4) covered += a.rgba[i] > 0;
    EXPECT_GT(covered, a.rgba.size() / 4 / 50) << "the views show the tree";
    EXPECT_EQ(connection->get(impostor["albedo_url"], {{"If-None-Match", albedo.header("etag")}}).status,
              304);
    EXPECT_EQ(connection->get(impostor["normal_url"]).status, 200);
    EXPECT_EQ(connection->get(impostor["exr_url"]).status, 200);
    EXPECT_EQ(impostor["radius"].get<double>() > 1.0, true);
}

TEST_F(ServeAssets, TheLayoutListsEveryViewWithItsFrame) {
    const Json& layout = (*summary)["impostor_layout"];
    EXPECT_EQ(layout["sphere"], "hemi-octahedral");
    EXPECT_EQ(layout["grid"], 4);
    EXPECT_EQ(layout["view_resolution"], 16);
    EXPECT_EQ(layout["atlas_size"], 64);
    ASSERT_EQ(layout["views"].size(), 16u);
    double best = -1.0;
    for (const Json& view : layout["views"]) {
        const glm::dvec3 d(view["direction"][0], view["direction"][1], view["direction"][2]);
        const glm::dvec3 r(view["right"][0], view["right"][1], view["right"][2]);
        const glm::dvec3 u(view["up"][0], view["up"][1], view["up"][2]);
        EXPECT_NEAR(glm::length(d), 1.0, 1e-5);
        EXPECT_GE(d.z, -1e-6); // the hemisphere in front of the wall
        EXPECT_NEAR(glm::dot(d, r), 0.0, 1e-5);
        EXPECT_NEAR(glm::dot(d, u), 0.0, 1e-5);
        best = std::max(best, d.z);
    }
    EXPECT_EQ(layout["views"][layout["central_view"].get<size_t>()]["direction"][2].get<double>(), best);
}

TEST_F(ServeAssets, EveryShapeMeshDecodesToTheLibraryMesh) {
    std::vector<const grammar::CompiledGrammar*> grammars;
    for (size_t g = 0; g < (*summary)["grammars"].size(); ++g) grammars.push_back(&grammarAt(g));
    const render::TerminalMeshLibrary library(grammars);
    for (size_t g = 0; g < grammars.size(); ++g) {
        for (size_t s = 0; s < library.shapeCount(uint32_t(g)); ++s) {
            const Json& shape = (*summary)["grammars"][g]["shapes"][s];
            tinygltf::Model model;
            ASSERT_TRUE(fetchGlb(shape["mesh_url"], model));
            const render::TerminalMesh& mesh = library.mesh(uint32_t(g), uint16_t(s));
            ASSERT_EQ(model.meshes.size(), 1u);
            const tinygltf::Accessor& positions =
                model.accessors.at(size_t(model.meshes[0].primitives.at(0).attributes.at("POSITION")));
            EXPECT_EQ(positions.count, mesh.vertices.size()) << mesh.shape;
            EXPECT_EQ(positions.maxValues.at(1), double(mesh.boundsMax.y)) << mesh.shape;
            EXPECT_EQ(shape["nominal_size"][0].get<float>(), mesh.nominalSize.x);
        }
    }
}

// Every shape whose generator has a coarser level that keeps its look (a finite deviation)
// carries a coarse mesh, facade parts and tree parts alike: that level with the deviation the
// native renderer decides with, served as its own .glb.
TEST_F(ServeAssets, ShapesCarryTheirCoarseMesh) {
    std::vector<const grammar::CompiledGrammar*> grammars;
    for (size_t g = 0; g < (*summary)["grammars"].size(); ++g) grammars.push_back(&grammarAt(g));
    const render::TerminalMeshLibrary library(grammars);
    size_t coarseTreeParts = 0, coarseFacadeParts = 0;
    for (size_t g = 0; g < grammars.size(); ++g) {
        const bool tree = (*summary)["grammars"][g]["kind"] == "tree";
        for (size_t s = 0; s < library.shapeCount(uint32_t(g)); ++s) {
            const Json& shape = (*summary)["grammars"][g]["shapes"][s];
            const render::TerminalMesh& fine = library.mesh(uint32_t(g), uint16_t(s));
            const std::optional<render::TerminalMesh> coarse =
                render::buildCoarserProceduralMesh(grammars[g]->shapes.at(s), fine);
            const glm::vec3 deviation = coarse ? render::meshDeviation(fine, *coarse) : glm::vec3(0.0f);
            const bool served = coarse && std::isfinite(deviation.x + deviation.y + deviation.z);
            ASSERT_EQ(shape["coarse_mesh"].is_null(), !served) << shape["name"];
            if (!served) continue;
            ++(tree ? coarseTreeParts : coarseFacadeParts);
            EXPECT_EQ(shape["coarse_mesh"]["triangles"], coarse->triangleCount());
            for (int a = 0; a < 3; ++a)
                EXPECT_EQ(shape["coarse_mesh"]["deviation"][a].get<float>(), deviation[a]) << shape["name"];
            tinygltf::Model model;
            ASSERT_TRUE(fetchGlb(shape["coarse_mesh"]["url"], model));
            const tinygltf::Accessor& indices =
                model.accessors.at(size_t(model.meshes.at(0).primitives.at(0).indices));
            EXPECT_EQ(indices.count, 3 * coarse->triangleCount()) << shape["name"];
            EXPECT_LT(indices.count, 3 * fine.triangleCount()) << shape["name"];
        }
    }
    EXPECT_GT(coarseTreeParts, 0u) << "the scene's trees have parts with a coarser level";
    EXPECT_GT(coarseFacadeParts, 0u) << "the scene's facades have parts with a coarser level";
}

TEST_F(ServeAssets, PngsAreTheAtlasAndAgreeWithTheStoredExr) {
    const Json& shape = (*summary)["grammars"][0]["shapes"][0];
    ASSERT_FALSE(shape["impostor"].is_null());
    const auto albedo = connection->get(shape["impostor"]["albedo_url"]);
    const auto normal = connection->get(shape["impostor"]["normal_url"]);
    const auto exr = connection->get(shape["impostor"]["exr_url"]);
    ASSERT_EQ(albedo.status, 200);
    ASSERT_EQ(normal.status, 200);
    ASSERT_EQ(exr.status, 200);
    EXPECT_EQ(exr.header("content-type"), "image/x-exr");
    const std::string exrPath = folder->file("fetched.exr");
    std::ofstream(exrPath, std::ios::binary) << exr.body;
    impostor::ImpostorAtlas atlas;
    std::string error;
    ASSERT_TRUE(impostor::readImpostorFile(exrPath, atlas, error)) << error;
    EXPECT_EQ(atlas.shape, shape["name"]);
    EXPECT_NEAR(atlas.radius, shape["impostor"]["radius"].get<double>(), 1e-6);

    const DecodedPng a = decodePng(albedo.body), n = decodePng(normal.body);
    ASSERT_EQ(a.width, 64);
    ASSERT_EQ(a.height, 64);
    ASSERT_EQ(n.width, 64);
    size_t covered = 0, empty = 0;
    for (uint32_t y = 0; y < 64; ++y) {
        for (uint32_t x = 0; x < 64; ++x) {
            const size_t i = (size_t(y) * 64 + x) * 4;
            const float* texel = atlas.albedo.at(x, y);
            const float* nd = atlas.normalDepth.at(x, y);
            // Coverage as the EXR holds it, to 8 bits.
            EXPECT_NEAR(a.rgba[i + 3] / 255.0, texel[3], 0.5 / 255.0 + 1e-3);
            if (texel[3] > 0.0f) {
                ++covered;
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(n.rgba[i + c] / 255.0, nd[c] * 0.5 + 0.5, 0.6 / 255.0);
                EXPECT_NEAR(n.rgba[i + 3] / 255.0, nd[3] * 0.5 + 0.5, 0.6 / 255.0);
            } else if (nd[3] <= -1.0f) {
                ++empty;
                EXPECT_EQ(n.rgba[i + 3], 0) << "an empty texel has depth -1: alpha 0";
            }
        }
    }
    EXPECT_GT(covered, 0u);
    EXPECT_GT(empty, 0u);
}

TEST_F(ServeAssets, ASecondStartLoadsEveryImpostorFromTheStore) {
    ServeProcess again(serveArguments(*folder, *scenePath, "second.jsonl")); // the first holds its journal
    ASSERT_TRUE(again.waitUntilServing(std::chrono::seconds(120))) << again.stderrText();
    const std::string log = again.stderrText();
    EXPECT_NE(log.find(": 0 new, "), std::string::npos) << "everything loaded: " << log;
    http_client::Connection c("127.0.0.1", again.port());
    const Json second = Json::parse(c.get("/api/v1/scene").body);
    EXPECT_EQ(second["grammars"][0]["shapes"], (*summary)["grammars"][0]["shapes"]) << "same keys, same URLs";
    EXPECT_EQ(again.stop(SIGTERM), 0);
}

TEST(ServeAssetsWithoutGl, MeshesAreServedAndTheNotesSayWhyImpostorsAreNot) {
    TemporaryFolder folder;
    const std::string scene = writeSmallScene(folder.path());
    std::vector<std::string> args = serveArguments(folder, scene);
    args.push_back("--no-impostors");
    ServeProcess serve(args);
    ASSERT_TRUE(serve.waitUntilServing()) << serve.stderrText();
    http_client::Connection c("127.0.0.1", serve.port());
    const Json s = Json::parse(c.get("/api/v1/scene").body);
    EXPECT_EQ(s["capabilities"]["terminal_meshes"], true);
    EXPECT_EQ(s["capabilities"]["impostors"], false);
    EXPECT_TRUE(s["impostor_layout"].is_null());
    EXPECT_EQ(note(s, "impostors (EXR, PNG): off"), "impostors (EXR, PNG): off (--no-impostors)");
    const Json& shape = s["grammars"][0]["shapes"][0];
    EXPECT_TRUE(shape["impostor"].is_null());
    EXPECT_EQ(c.get(shape["mesh_url"]).status, 200);
    EXPECT_EQ(c.get("/api/v1/impostors/0/0/0000000000000000.exr").status, 501);
    EXPECT_FALSE(std::filesystem::exists(folder.file("store"))) << "no bake, no store";
    EXPECT_EQ(serve.stop(SIGTERM), 0);
}

TEST(ServeAssetsWithoutBuildings, TreesGetTheirSpeciesAndNoFacadeIsBaked) {
    TemporaryFolder folder;
    const std::string scene = writeTreesOnlyScene(folder);
    ServeProcess serve(serveArguments(folder, scene));
    ASSERT_TRUE(serve.waitUntilServing(std::chrono::seconds(120))) << serve.stderrText();
    http_client::Connection c("127.0.0.1", serve.port());
    const Json s = Json::parse(c.get("/api/v1/scene").body);
    EXPECT_EQ(s["capabilities"]["tree_billboards"], true);
    EXPECT_FALSE(s["tree_species"].empty());
    for (const Json& grammar : s["grammars"])
        for (const Json& shape : grammar["shapes"]) EXPECT_TRUE(shape["impostor"].is_null()) << shape["name"];
    EXPECT_NE(note(s, "impostors: 0 of "), "") << "no facade shape baked";
    EXPECT_EQ(serve.stop(SIGTERM), 0);
}

// An edit that gives trees values no species has: while it runs, the service bakes one species
// per new value set (a "species" event, without id), lists it with the exact values, serves its
// files and counts it in the hello and the metrics. Values it serves already bake nothing: the
// undo back to the start's values, and the same edit made again.
TEST(ServeSpeciesForEdits, EditedTreesGetSpeciesOfTheirNewValues) {
    TemporaryFolder folder;
    const std::string scene = writeTreesOnlyScene(folder);
    ServeProcess serve(serveArguments(folder, scene));
    ASSERT_TRUE(serve.waitUntilServing(std::chrono::seconds(120))) << serve.stderrText();
    http_client::Connection c("127.0.0.1", serve.port());
    const Json before = Json::parse(c.get("/api/v1/scene").body);
    const size_t started = before["tree_species"].size();
    ASSERT_GT(started, 0u);
    const scene::BuiltScene built = buildSmallScene(scene);
    ASSERT_EQ(built.treeGrammars.size(), 1u);
    const uint32_t grammar = uint32_t(built.buildingGrammars.size());
    const std::vector<grammar::ParameterInfo>& params = built.treeGrammars[0].grammar.params;
    const size_t trunk =
        size_t(std::find_if(params.begin(), params.end(),
                            [](const grammar::ParameterInfo& p) { return p.name == "trunk_h"; }) -
               params.begin());
    ASSERT_LT(trunk, params.size());
    std::set<std::vector<float>> expected;
    for (const grammar::BuildingInput& tree : built.treeGrammars[0].buildings) {
        std::vector<float> values = tree.parameters;
        values[trunk] = 4.25f;
        expected.insert(values);
    }

    http_client::EventStreamReader events("127.0.0.1", serve.port(), "/api/v1/events");
    const auto hello = events.next(std::chrono::seconds(5));
    ASSERT_TRUE(hello);
    EXPECT_EQ(Json::parse(hello->data)["tree_species"], started);
    const std::string edit =
        R"({"selector":{"grammar":)" + std::to_string(grammar) + R"(},"params":{"trunk_h":4.25}})";
    ASSERT_EQ(c.post("/api/v1/edits", edit).status, 200);
    const auto edited = events.next(std::chrono::seconds(5));
    ASSERT_TRUE(edited);
    EXPECT_EQ(edited->event, "edit");

    std::set<std::vector<float>> baked;
    for (size_t k = 0; k < expected.size(); ++k) {
        const auto event = events.next(std::chrono::seconds(60));
        ASSERT_TRUE(event) << "species " << k << " of " << expected.size() << "\n" << serve.stderrText();
        ASSERT_EQ(event->event, "species") << event->data;
        EXPECT_EQ(event->id, "") << "not an edit: no id, not replayed";
        const Json data = Json::parse(event->data);
        const Json& species = data["species"];
        EXPECT_EQ(species["index"], started + k);
        EXPECT_EQ(data["tree_species"], started + k + 1);
        EXPECT_EQ(species["grammar"], grammar);
        baked.insert(species["parameters"].get<std::vector<float>>());
        const auto albedo = c.get(species["impostor"]["albedo_url"].get<std::string>());
        ASSERT_EQ(albedo.status, 200);
        EXPECT_EQ(albedo.header("content-type"), "image/png");
        const DecodedPng png = decodePng(albedo.body);
        size_t covered = 0;
        for (size_t i = 3; i < png.rgba.size(); i += 4) covered += png.rgba[i] > 0;
        EXPECT_GT(covered, png.rgba.size() / 4 / 50) << "the views show the edited tree";
    }
    EXPECT_EQ(baked, expected) << "one species per new value set, with exactly those values";
    const Json after = Json::parse(c.get("/api/v1/scene").body);
    EXPECT_EQ(after["tree_species"].size(), started + expected.size());
    EXPECT_NE(
        c.get("/metrics")
            .body.find("hexlod_tree_species{state=\"served\"} " + std::to_string(started + expected.size())),
        std::string::npos);

    ASSERT_EQ(c.post("/api/v1/edits/undo", "").status, 200);
    ASSERT_EQ(c.post("/api/v1/edits", edit).status, 200);
    for (const char* kind : {"undo", "edit"}) {
        const auto event = events.next(std::chrono::seconds(5));
        ASSERT_TRUE(event);
        EXPECT_EQ(event->event, kind);
    }
    const auto extra = events.next(std::chrono::seconds(3));
    EXPECT_FALSE(extra) << "nothing baked again: " << (extra ? extra->event + " " + extra->data : "");
    http_client::EventStreamReader later("127.0.0.1", serve.port(), "/api/v1/events");
    const auto laterHello = later.next(std::chrono::seconds(5));
    ASSERT_TRUE(laterHello);
    EXPECT_EQ(Json::parse(laterHello->data)["tree_species"], started + expected.size());
    EXPECT_EQ(serve.stop(SIGTERM), 0);
}

TEST(ServeAssetsOptions, BadImpostorOptionsAreRefusedByName) {
    TemporaryFolder folder;
    const std::string scene = writeSmallScene(folder.path());
    for (const auto& [option, value, message] :
         {std::tuple{"--impostor-grid", "1", "--impostor-grid: 1 is outside [2, 32]"},
          std::tuple{"--impostor-res", "4096", "--impostor-res: 4096 is outside [16, 1024]"},
          std::tuple{"--gl", "vulkan", "--gl: unknown backend 'vulkan'"}}) {
        std::vector<std::string> args = baseArguments(folder, scene);
        args.push_back(option);
        args.push_back(value);
        ServeProcess serve(args);
        EXPECT_FALSE(serve.waitUntilServing(std::chrono::seconds(30)));
        EXPECT_EQ(serve.wait(), 2) << option;
        EXPECT_NE(serve.stderrText().find(message), std::string::npos) << serve.stderrText();
    }
}

} // namespace
} // namespace hexlod::test
