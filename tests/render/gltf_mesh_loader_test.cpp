// glTF user shapes: the shared Kenney models load, are fitted to unit scope space and keep their
// colours; malformed files made here are clear errors naming the file, never crashes.
#include "hexlod/render/gltf_mesh_loader.h"
#include "hexlod/render/terminal_mesh_library.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <set>

namespace hexlod::render {
namespace {

const std::string kMeshes = std::string(HEXLOD_SHARED_DATA_DIR) + "/meshes/";
const glm::vec3 kDoorNominal = nominalShapeSize(1.2f, 2.3f, 0.06f);

std::string tempPath(const std::string& name) {
    return ::testing::TempDir() + "hexlod-gltf-" + name;
}

std::string writeFile(const std::string& name, const std::string& bytes) {
    const std::string path = tempPath(name);
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

void expectUnitScope(const TerminalMesh& m) {
    EXPECT_NEAR(m.boundsMin.x, 0.0f, 1e-5f);
    EXPECT_NEAR(m.boundsMax.x, 1.0f, 1e-5f);
    EXPECT_NEAR(m.boundsMin.y, 0.0f, 1e-5f);
    EXPECT_NEAR(m.boundsMax.y, 1.0f, 1e-5f);
    EXPECT_GE(m.boundsMin.z, -1e-5f);
    EXPECT_LE(m.boundsMax.z, 1.0f + 1e-5f);
    for (const uint32_t i : m.indices) ASSERT_LT(i, m.vertices.size());
    for (const MeshVertex& v : m.vertices) EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-4f);
}

TEST(GltfMeshLoader, LoadsTheKenneyDoor) {
    const std::string path = kMeshes + "kenney_platformer_kit/door.glb";
    const GltfLoadResult r = loadGltfMesh(path, "door", kDoorNominal);
    ASSERT_TRUE(r.ok) << r.error;
    const TerminalMesh& m = r.mesh;
    // Three primitives on two nodes (the child moved by its translation): 180 + 270 + 270
    // vertices and (348 + 309 + 219) / 3 triangles.
    EXPECT_EQ(m.vertices.size(), 720u);
    EXPECT_EQ(m.triangleCount(), 292u);
    EXPECT_EQ(m.source, path);
    EXPECT_EQ(m.shape, "door");
    expectUnitScope(m);
    EXPECT_NEAR(m.boundsMin.z, 0.0f, 1e-5f);
    EXPECT_NEAR(m.boundsMax.z, 1.0f, 1e-5f);
    // Material colours (metal, wood, dark wood) reach the vertices.
    std::set<uint32_t> colours;
    for (const MeshVertex& v : m.vertices) colours.insert(v.rgba);
    EXPECT_EQ(colours.size(), 3u);
    EXPECT_TRUE(colours.count(packRgba(0.8666667f, 0.533333361f, 0.309803933f))) << "wood";
    // The child node's leaf sits at x in [0.45, 0.55] of the model's [0.4, 0.6]: unit [0.25, 0.75].
    float leafMin = 1.0f, leafMax = 0.0f;
    for (const MeshVertex& v : m.vertices) {
        if (v.rgba == packRgba(0.8666667f, 0.533333361f, 0.309803933f)) {
            leafMin = std::min(leafMin, v.position.x);
            leafMax = std::max(leafMax, v.position.x);
        }
    }
    EXPECT_NEAR(leafMin, 0.25f, 1e-4f);
    EXPECT_NEAR(leafMax, 0.75f, 1e-4f);
}

TEST(GltfMeshLoader, LoadsOtherKenneyModelsWithTexturesAndVertexColours) {
    // The tree has two materials, the building a palette texture (colormap.png, sampled per vertex).
    for (const char* file :
         {"kenney_platformer_kit/tree.glb", "kenney_city_builder/models/building-small-a.glb"}) {
        SCOPED_TRACE(file);
        const GltfLoadResult r = loadGltfMesh(kMeshes + file, "shape", glm::vec3(2.0f, 3.0f, 1.0f));
        ASSERT_TRUE(r.ok) << r.error;
        expectUnitScope(r.mesh);
        EXPECT_GT(r.mesh.triangleCount(), 50u);
        std::set<uint32_t> colours;
        for (const MeshVertex& v : r.mesh.vertices) colours.insert(v.rgba);
        EXPECT_GE(colours.size(), 2u) << "a palette texture or materials give several colours";
        EXPECT_FALSE(colours.count(packRgba(1, 1, 1))) << "untextured white would mean the colours were lost";
    }
}

TEST(GltfMeshLoader, NormalsAreForTheNominalSize) {
    // The same model fitted to a flat, wide shape: its normals lean towards t, where the
    // stretch squeezed the model least.
    const std::string path = kMeshes + "kenney_platformer_kit/crate.glb";
    const GltfLoadResult cube = loadGltfMesh(path, "crate", glm::vec3(1.0f));
    const GltfLoadResult wide = loadGltfMesh(path, "crate", glm::vec3(10.0f, 10.0f, 1.0f));
    ASSERT_TRUE(cube.ok && wide.ok) << cube.error << wide.error;
    ASSERT_EQ(cube.mesh.vertices.size(), wide.mesh.vertices.size());
    for (size_t i = 0; i < cube.mesh.vertices.size(); ++i) {
        const glm::vec3 n = cube.mesh.vertices[i].normal, w = wide.mesh.vertices[i].normal;
        const glm::vec3 expected = glm::normalize(n / glm::vec3(10.0f, 10.0f, 1.0f));
        EXPECT_NEAR(glm::dot(w, expected), 1.0f, 1e-4f);
    }
}

// Minimal glTF JSON with an embedded base64 buffer, for the malformed cases.
std::string triangleGltf(const std::string& positions, const std::string& extra = "") {
    return R"({"asset": {"version": "2.0"}, )" + extra +
           R"("buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)" + positions +
           R"("}], "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}], "scene": 0})";
}

std::string base64(const std::string& bytes) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 2]));
        out += table[(v >> 18) & 63];
        out += table[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? table[v & 63] : '=';
    }
    return out;
}

std::string floats(std::initializer_list<float> values) {
    std::string bytes(values.size() * 4, '\0');
    size_t i = 0;
    for (const float v : values) std::memcpy(&bytes[4 * i++], &v, 4);
    return bytes;
}

TEST(GltfMeshLoader, ATriangleWithoutNormalsGetsComputedOnes) {
    const std::string path =
        writeFile("triangle.gltf", triangleGltf(base64(floats({0, 0, 0, 2, 0, 0, 0, 3, 0}))));
    const GltfLoadResult r = loadGltfMesh(path, "s", glm::vec3(1.0f, 1.0f, 0.5f));
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.mesh.triangleCount(), 1u);
    for (const MeshVertex& v : r.mesh.vertices) {
        EXPECT_EQ(v.position.z, 0.0f); // flat in z: at the wall plane
        EXPECT_NEAR(v.normal.z, 1.0f, 1e-6f);
    }
}

TEST(GltfMeshLoader, VertexColoursOfEveryEncodingTimesTheBaseColour) {
    // COLOR_0 as normalised unsigned bytes (vec4), normalised unsigned shorts (vec3) and floats
    // (vec4), each multiplied by the material's baseColorFactor.
    std::string bytes = floats({0, 0, 0, 2, 0, 0, 0, 3, 1});
    bytes += std::string("\xff\x00\x80\xff"
                         "\x00\xff\x00\x80"
                         "\x40\x40\x40\xff",
                         12);
    const uint16_t shorts[9] = {65535, 0, 0, 0, 65535, 0, 0, 0, 65535};
    bytes += std::string(reinterpret_cast<const char*>(shorts), sizeof(shorts)) + std::string(2, '\0');
    bytes += floats({0.25f, 0.5f, 1.0f, 1.0f, 1, 1, 1, 1, 0, 0, 0, 1});
    const std::string json = R"({"asset": {"version": "2.0"},
        "buffers": [{"byteLength": )" +
                             std::to_string(bytes.size()) +
                             R"(, "uri": "data:application/octet-stream;base64,)" + base64(bytes) + R"("}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 12},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 18}, {"buffer": 0, "byteOffset": 68, "byteLength": 48}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                      {"bufferView": 1, "componentType": 5121, "normalized": true, "count": 3, "type": "VEC4"},
                      {"bufferView": 2, "componentType": 5123, "normalized": true, "count": 3, "type": "VEC3"},
                      {"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC4"}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 1, 1, 1]}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "COLOR_0": 1}, "material": 0},
                                   {"attributes": {"POSITION": 0, "COLOR_0": 2}},
                                   {"attributes": {"POSITION": 0, "COLOR_0": 3}}]}]})";
    const std::string path = writeFile("colours.gltf", json);
    const GltfLoadResult r = loadGltfMesh(path, "s", glm::vec3(1.0f));
    ASSERT_TRUE(r.ok) << r.error;
    ASSERT_EQ(r.mesh.vertices.size(), 9u);
    const auto colour = [&](size_t i) { return r.mesh.vertices[i].rgba; };
    EXPECT_EQ(colour(0), packRgba(0.5f, 0.0f, 128.0f / 255.0f, 1.0f)); // red halved by the factor
    EXPECT_EQ(colour(1), packRgba(0.0f, 1.0f, 0.0f, 128.0f / 255.0f));
    EXPECT_EQ(colour(3), packRgba(1.0f, 0.0f, 0.0f, 1.0f)); // vec3 gets alpha 1
    EXPECT_EQ(colour(5), packRgba(0.0f, 0.0f, 1.0f, 1.0f));
    EXPECT_EQ(colour(6), packRgba(0.25f, 0.5f, 1.0f, 1.0f));
    EXPECT_EQ(r.mesh.triangleCount(), 3u);
}

struct BadCase {
    const char* name;
    std::string bytes;
    const char* message;
};

TEST(GltfMeshLoader, MalformedFilesAreErrorsNamingTheFile) {
    const std::string door = readFile(kMeshes + "kenney_platformer_kit/door.glb");
    ASSERT_GT(door.size(), 1000u);
    const std::string nan = base64(floats({0, 0, 0, std::nanf(""), 0, 0, 0, 1, 0}));
    const std::string huge = base64(floats({0, 0, 0, 1e7f, 0, 0, 0, 1, 0}));
    const std::string line = base64(floats({0, 0, 0, 1, 0, 0, 2, 0, 0}));
    std::string badChunk = door;
    badChunk[12] = '\xff'; // JSON chunk length far past the end
    const BadCase cases[] = {
        {"truncated.glb", door.substr(0, door.size() / 2), "not a readable glTF binary"},
        {"header-only.glb", door.substr(0, 12), "not a readable glTF binary"},
        {"bad-chunk.glb", badChunk, "not a readable glTF binary"},
        {"garbage.glb", std::string(4096, '\x5a'), "not a readable glTF file"},
        {"empty.gltf", "", "not a readable glTF file"},
        {"empty-object.gltf", "{}", ""},
        {"no-meshes.gltf", R"({"asset": {"version": "2.0"}})", "no triangles"},
        {"nan.gltf", triangleGltf(nan), "not finite"},
        {"huge.gltf", triangleGltf(huge), "larger than 1e6 m"},
        {"degenerate.gltf", triangleGltf(line), "degenerate"},
        {"draco.gltf", triangleGltf(line, R"("extensionsUsed": ["KHR_draco_mesh_compression"],
            "extensionsRequired": ["KHR_draco_mesh_compression"], )"),
         "KHR_draco_mesh_compression"},
        {"short-buffer.gltf",
         R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 12, "uri": "data:application/octet-stream;base64,)" +
             base64(floats({0, 0, 0})) + R"("}], "bufferViews": [{"buffer": 0, "byteLength": 12}],
             "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
             "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}]})",
         "past the end"},
    };
    for (const BadCase& c : cases) {
        SCOPED_TRACE(c.name);
        const std::string path = writeFile(c.name, c.bytes);
        const GltfLoadResult r = loadGltfMesh(path, "s", glm::vec3(1.0f));
        EXPECT_FALSE(r.ok);
        EXPECT_EQ(r.error.rfind(path + ": ", 0), 0u) << r.error;
        EXPECT_NE(r.error.find(c.message), std::string::npos) << r.error;
    }
    const GltfLoadResult missing = loadGltfMesh("/nonexistent/door.glb", "s", glm::vec3(1.0f));
    EXPECT_FALSE(missing.ok);
    EXPECT_EQ(missing.error, "/nonexistent/door.glb: no such file");
}

TEST(GltfMeshLoader, TheLibraryUsesGltfSourcesAndFallsBackOnErrors) {
    grammar::DiagnosticList diagnostics;
    const grammar::CompiledGrammar g = grammar::compileGrammar(
        "shape door(width = 1.2, height = 2.3, depth_ratio = 0.06, triangles = 180);\n"
        "shape gizmo(width = 1, height = 1, depth_ratio = 0.5, triangles = 12);\n"
        "shape ledge(width = 3, height = 0.3, depth_ratio = 1, triangles = 54);\n"
        "A -> Split(x, ~1, ~1, ~1) { Door, Gizmo, Ledge };\nDoor -> Shape(door);\n"
        "Gizmo -> Shape(gizmo);\nLedge -> Shape(ledge);\n",
        "test.grammar", diagnostics);
    ASSERT_FALSE(g.rules.empty()) << diagnostics.formatAll();
    const grammar::CompiledGrammar* grammars[] = {&g, &g};
    const GltfShapeSource sources[] = {{"door", kMeshes + "kenney_platformer_kit/door.glb"},
                                       {"ledge", "/nonexistent/ledge.glb"},
                                       {"roof", kMeshes + "kenney_platformer_kit/block.glb"}};
    const TerminalMeshLibrary library(grammars, sources);
    ASSERT_EQ(library.grammarCount(), 2u);
    EXPECT_EQ(library.shapeCount(1), 3u);
    EXPECT_EQ(library.mesh(0, 0).source, kMeshes + "kenney_platformer_kit/door.glb");
    EXPECT_EQ(library.mesh(0, 1).source, "fallback");
    EXPECT_EQ(library.mesh(0, 2).source, "procedural");
    EXPECT_EQ(library.shared(0, 0), library.shared(1, 0)) << "one mesh object per identical declaration";
    EXPECT_EQ(library.distinctMeshCount(), 3u);
    EXPECT_EQ(library.fallbackCount(), 1u);
    EXPECT_EQ(library.find(0, 3), nullptr);
    EXPECT_EQ(library.find(2, 0), nullptr);
    EXPECT_THROW(library.mesh(0, 3), std::out_of_range);
    std::string notes;
    for (const std::string& note : library.notes()) notes += note + "\n";
    EXPECT_NE(notes.find("shape 'gizmo' (grammar test.grammar): no procedural generator"), std::string::npos)
        << notes;
    EXPECT_NE(notes.find("/nonexistent/ledge.glb: no such file; using its procedural mesh"),
              std::string::npos)
        << notes;
    EXPECT_NE(notes.find("shapes.roof: no grammar of the scene declares this shape"), std::string::npos)
        << notes;
    EXPECT_GT(library.byteSize(), library.mesh(0, 0).byteSize());
}

} // namespace
} // namespace hexlod::render
