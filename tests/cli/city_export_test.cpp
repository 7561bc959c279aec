// The glTF city export at library level on hand-built scenes: instances match the terminal
// sets, decoded instance transforms put the unit mesh on its terminal's scope within a
// millimetre, also 1e7 m from the origin, --flatten keeps the world-space triangles, and
// over-large exports are refused cleanly.
#include "city_gltf_export.h"
#include "shape_mesh_glb.h"

#include "hexlod/render/terminal_mesh_library.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <glm/gtc/quaternion.hpp>

#include <filesystem>
#include <map>

namespace hexlod::apps {
namespace {

grammar::CompiledGrammar thesisGrammar() {
    grammar::DiagnosticList diagnostics;
    grammar::CompiledGrammar g = grammar::compileGrammarFile(
        std::string(HEXLOD_CONFIGS_DIR) + "/grammars/thesis-example.grammar", diagnostics);
    EXPECT_FALSE(g.rules.empty()) << diagnostics.formatAll();
    return g;
}

// Rectangular lots in a row starting at `corner`, on 100 m cells so that they span two cells.
scene::BuiltScene rowOfBuildings(glm::dvec2 corner, int count) {
    scene::BuiltScene built;
    built.config.name = "row";
    built.config.cellSize = 100.0;
    built.config.seed = 5;
    scene::GrammarBuildings grammar{"thesis", thesisGrammar(), {}};
    for (int i = 0; i < count; ++i) {
        const glm::dvec2 a = corner + glm::dvec2(60.0 * i, 0.0);
        grammar::BuildingInput b;
        b.id = uint32_t(i);
        b.footprint = {a, a + glm::dvec2(20, 0), a + glm::dvec2(20, 12), a + glm::dvec2(0, 12)};
        b.baseElevation = 2.0;
        grammar.buildings.push_back(b);
    }
    built.buildingGrammars.push_back(std::move(grammar));
    return built;
}

// A scene's catalog with its mesh library.
struct Prepared {
    cells::BatchCatalog catalog;
    render::TerminalMeshLibrary library;

    explicit Prepared(scene::BuiltScene scene) : catalog(std::move(scene)) {
        std::vector<const grammar::CompiledGrammar*> grammars;
        for (uint32_t g = 0; g < catalog.index().grammarCount(); ++g)
            grammars.push_back(&catalog.grammar(g).grammar);
        library = render::TerminalMeshLibrary(grammars);
    }
};

// An empty folder of its own for one test's files.
std::string freshDirectory(const std::string& name) {
    const std::string dir = ::testing::TempDir() + name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

struct Exported : Prepared {
    CityExportReport report;
    tinygltf::Model model;
    using Prepared::Prepared;
};

std::unique_ptr<Exported> exportScene(scene::BuiltScene scene, const std::string& name, bool flatten) {
    auto e = std::make_unique<Exported>(std::move(scene));
    CityExportOptions options;
    options.output = ::testing::TempDir() + name;
    options.flatten = flatten;
    e->report = exportCityGltf(e->catalog, e->library, options);
    EXPECT_TRUE(e->report.ok) << e->report.error;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    EXPECT_TRUE(loader.LoadBinaryFromFile(&e->model, &err, &warn, options.output)) << err;
    return e;
}

template <class T> std::vector<T> readAccessor(const tinygltf::Model& m, int index) {
    const tinygltf::Accessor& a = m.accessors.at(size_t(index));
    const tinygltf::BufferView& v = m.bufferViews.at(size_t(a.bufferView));
    const size_t components = size_t(tinygltf::GetNumComponentsInType(uint32_t(a.type)));
    const size_t stride = v.byteStride ? v.byteStride : components * sizeof(T);
    std::vector<T> out;
    const unsigned char* base = m.buffers.at(size_t(v.buffer)).data.data() + v.byteOffset + a.byteOffset;
    for (size_t i = 0; i < a.count; ++i) {
        for (size_t c = 0; c < components; ++c) {
            T value;
            std::memcpy(&value, base + i * stride + c * sizeof(T), sizeof(T));
            out.push_back(value);
        }
    }
    return out;
}

glm::dvec3 numbers3(const std::vector<double>& v) {
    return v.size() == 3 ? glm::dvec3(v[0], v[1], v[2]) : glm::dvec3(0.0);
}

// World positions (hexlod frame, double) of unit-space points under every instance, by mesh name.
std::map<std::string, std::vector<glm::dvec3>> decodedCorners(const tinygltf::Model& m,
                                                              const glm::dvec3& unit) {
    const tinygltf::Value& origin = m.asset.extras.Get("hexlod").Get("origin");
    const glm::dvec3 reference(origin.Get(0).GetNumberAsDouble(), origin.Get(1).GetNumberAsDouble(),
                               origin.Get(2).GetNumberAsDouble());
    std::map<std::string, std::vector<glm::dvec3>> out;
    for (const int cellNode : m.nodes.at(0).children) {
        const tinygltf::Node& cell = m.nodes.at(size_t(cellNode));
        const glm::dvec3 cellOffset = reference + numbers3(cell.translation);
        for (const int child : cell.children) {
            const tinygltf::Node& node = m.nodes.at(size_t(child));
            const auto ext = node.extensions.find("EXT_mesh_gpu_instancing");
            if (ext == node.extensions.end()) continue;
            const tinygltf::Value& attributes = ext->second.Get("attributes");
            const auto t = readAccessor<float>(m, attributes.Get("TRANSLATION").GetNumberAsInt());
            const auto r = readAccessor<float>(m, attributes.Get("ROTATION").GetNumberAsInt());
            const auto s = readAccessor<float>(m, attributes.Get("SCALE").GetNumberAsInt());
            for (size_t i = 0; i < t.size() / 3; ++i) {
                const glm::dquat q(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]);
                const glm::dvec3 scaled = unit * glm::dvec3(s[3 * i], s[3 * i + 1], s[3 * i + 2]);
                out[node.name].push_back(cellOffset + glm::dvec3(t[3 * i], t[3 * i + 1], t[3 * i + 2]) +
                                         q * scaled);
            }
        }
    }
    return out;
}

// The same corners computed from the catalog's terminal sets, in double.
std::map<std::string, std::vector<glm::dvec3>> expectedCorners(const cells::BatchCatalog& catalog,
                                                               const glm::dvec3& unit) {
    std::map<std::string, std::vector<glm::dvec3>> out;
    for (uint32_t b = 0; b < catalog.batchCount(); ++b) {
        const grammar::TerminalSet set = catalog.generate(b);
        const glm::dvec3 origin = catalog.cellOrigin(catalog.batch(b).cell);
        const grammar::CompiledGrammar& g = catalog.grammar(catalog.batch(b).grammar).grammar;
        for (const grammar::TerminalRecord& record : set.records) {
            const grammar::Terminal t = grammar::unpackTerminal(record);
            const double w = t.size.x, h = t.size.y, d = double(t.depthRatio) * std::min(w, h);
            const glm::dvec3 x = glm::dvec3(t.axisX()), y = glm::dvec3(t.axisY()), z = glm::dvec3(t.normal());
            out["thesis/" + g.shapes[t.shape].name].push_back(origin + glm::dvec3(t.position) +
                                                              unit.x * w * x + unit.y * h * y +
                                                              unit.z * std::max(d, 1e-4) * z);
        }
    }
    return out;
}

void expectSameCorners(const Exported& e) {
    for (const glm::dvec3 unit : {glm::dvec3(0.0), glm::dvec3(1.0), glm::dvec3(0.3, 0.8, -1.0)}) {
        const auto decoded = decodedCorners(e.model, unit), expected = expectedCorners(e.catalog, unit);
        ASSERT_EQ(decoded.size(), expected.size());
        for (const auto& [name, points] : expected) {
            SCOPED_TRACE(name);
            const std::vector<glm::dvec3>& got = decoded.at(name);
            ASSERT_EQ(got.size(), points.size()) << "instances = terminals of the shape";
            for (size_t i = 0; i < points.size(); ++i) {
                ASSERT_LT(glm::length(got[i] - points[i]), 1e-3) << "instance " << i;
            }
        }
    }
}

TEST(CityExport, InstancesAreTheTerminalsAndLandOnTheirScopes) {
    const auto e = exportScene(rowOfBuildings({-40.0, 10.0}, 4), "row.glb", false);
    EXPECT_GE(e->report.cells, 2u);
    EXPECT_EQ(e->report.instances, e->report.terminals);
    EXPECT_EQ(e->model.extensionsRequired, std::vector<std::string>{"EXT_mesh_gpu_instancing"});
    uint64_t terminals = 0;
    std::map<std::string, uint64_t> perShape;
    for (uint32_t b = 0; b < e->catalog.batchCount(); ++b) {
        const grammar::TerminalSet set = e->catalog.generate(b);
        terminals += set.records.size();
        for (size_t s = 0; s < set.countPerShape.size(); ++s) {
            if (set.countPerShape[s])
                perShape["thesis/" + e->catalog.grammar(0).grammar.shapes[s].name] += set.countPerShape[s];
        }
    }
    EXPECT_EQ(e->report.terminals, terminals);
    EXPECT_EQ(e->report.instancesPerMesh, perShape);
    // Each terminal mesh once: four thesis shapes, plus one base-volume mesh per cell.
    EXPECT_EQ(e->report.terminalMeshes, 4u);
    EXPECT_EQ(e->model.meshes.size(), 4u + e->report.cells);
    expectSameCorners(*e);
}

TEST(CityExport, KeepsMillimetresTenThousandKilometresOut) {
    const auto e = exportScene(rowOfBuildings({1e7 + 3.25, -1e7 + 7.5}, 4), "far.glb", false);
    EXPECT_GT(std::abs(e->report.origin.x), 9.9e6);
    expectSameCorners(*e);
}

uint64_t fileTriangles(const tinygltf::Model& m) {
    uint64_t triangles = 0;
    for (const tinygltf::Node& node : m.nodes) {
        if (node.mesh < 0) continue;
        uint64_t instances = 1;
        const auto ext = node.extensions.find("EXT_mesh_gpu_instancing");
        if (ext != node.extensions.end())
            instances =
                m.accessors.at(size_t(ext->second.Get("attributes").Get("TRANSLATION").GetNumberAsInt()))
                    .count;
        for (const tinygltf::Primitive& p : m.meshes.at(size_t(node.mesh)).primitives)
            triangles += instances * m.accessors.at(size_t(p.indices)).count / 3;
    }
    return triangles;
}

TEST(CityExport, FlattenKeepsTheWorldSpaceTriangles) {
    const auto instanced = exportScene(rowOfBuildings({0.0, 0.0}, 3), "instanced.glb", false);
    const auto flat = exportScene(rowOfBuildings({0.0, 0.0}, 3), "flat.glb", true);
    EXPECT_EQ(instanced->report.triangles, flat->report.triangles);
    EXPECT_EQ(fileTriangles(instanced->model), instanced->report.triangles);
    EXPECT_EQ(fileTriangles(flat->model), flat->report.triangles);
    EXPECT_TRUE(flat->model.extensionsUsed.empty());
    EXPECT_GT(flat->report.bytes, instanced->report.bytes);
    EXPECT_GT(instanced->report.baseVolumeTriangles, 0u);
}

TEST(CityExport, RefusesPastItsLimitAndLeavesNothingBehind) {
    const Prepared scene(rowOfBuildings({0.0, 0.0}, 3));
    const cells::BatchCatalog& catalog = scene.catalog;
    const render::TerminalMeshLibrary& library = scene.library;
    const std::string dir = freshDirectory("hexlod-export-limit");
    CityExportOptions options;
    options.output = dir + "/city.glb";
    options.maxBytes = 20000;
    const CityExportReport report = exportCityGltf(catalog, library, options);
    EXPECT_FALSE(report.ok);
    EXPECT_NE(report.error.find("limit of 20000 bytes"), std::string::npos) << report.error;
    EXPECT_TRUE(std::filesystem::is_empty(dir)) << "no output and no temporary files";

    options.maxBytes = 0;
    options.cells = {{40, 40}};
    EXPECT_EQ(exportCityGltf(catalog, library, options).error, "cell 40,40 holds no buildings or trees");
    options.cells = {};
    options.output = dir + "/city.obj";
    EXPECT_NE(exportCityGltf(catalog, library, options).error.find("written as .glb or .gltf"),
              std::string::npos);
}

TEST(CityExport, WritesGltfWithItsBufferBeside) {
    const Prepared scene(rowOfBuildings({0.0, 0.0}, 2));
    const std::string dir = freshDirectory("hexlod-export-gltf");
    CityExportOptions options;
    options.output = dir + "/city.gltf";
    const CityExportReport report = exportCityGltf(scene.catalog, scene.library, options);
    ASSERT_TRUE(report.ok) << report.error;
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadASCIIFromFile(&model, &err, &warn, options.output)) << err;
    EXPECT_EQ(model.buffers.at(0).uri, "city.bin");
    EXPECT_EQ(report.bytes,
              std::filesystem::file_size(options.output) + std::filesystem::file_size(dir + "/city.bin"));
}

// The JSON chunk of a .glb (its length at byte 12, its text from byte 20).
nlohmann::json glbJson(const std::vector<uint8_t>& glb) {
    uint32_t length = 0;
    std::memcpy(&length, glb.data() + 12, 4);
    return nlohmann::json::parse(glb.begin() + 20, glb.begin() + 20 + length);
}

// A shape's .glb as the service hands it out: every vertex of the library mesh in unit scope
// space with the unit-space normal, the colour, the triangles, and the nominal size recorded.
TEST(ShapeMeshGlb, CarriesTheUnitScopeMeshExactly) {
    const Prepared scene(rowOfBuildings({0.0, 0.0}, 1));
    for (uint16_t s = 0; s < scene.library.shapeCount(0); ++s) {
        const render::TerminalMesh& mesh = scene.library.mesh(0, s);
        const std::vector<uint8_t> glb = shapeMeshGlb(mesh, mesh.shape);
        ASSERT_EQ(glb.size() % 4, 0u);
        tinygltf::Model model;
        tinygltf::TinyGLTF loader;
        std::string err, warn;
        ASSERT_TRUE(loader.LoadBinaryFromMemory(&model, &err, &warn, glb.data(), unsigned(glb.size())))
            << err;
        const nlohmann::json extras = glbJson(glb)["asset"]["extras"]["hexlod"];
        EXPECT_EQ(extras["nominal_size"][0].get<float>(), mesh.nominalSize.x);
        ASSERT_EQ(model.meshes.size(), 1u);
        EXPECT_EQ(model.meshes[0].name, mesh.shape);
        const tinygltf::Primitive& p = model.meshes[0].primitives.at(0);
        const std::vector<float> positions = readAccessor<float>(model, p.attributes.at("POSITION"));
        const std::vector<float> normals = readAccessor<float>(model, p.attributes.at("NORMAL"));
        const std::vector<uint8_t> colours = readAccessor<uint8_t>(model, p.attributes.at("COLOR_0"));
        const std::vector<uint32_t> indices = readAccessor<uint32_t>(model, p.indices);
        ASSERT_EQ(positions.size(), 3 * mesh.vertices.size());
        ASSERT_EQ(colours.size(), 4 * mesh.vertices.size());
        EXPECT_EQ(indices, mesh.indices);
        for (size_t v = 0; v < mesh.vertices.size(); ++v) {
            const render::MeshVertex& in = mesh.vertices[v];
            EXPECT_EQ(glm::vec3(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]), in.position);
            const glm::vec3 n(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
            EXPECT_EQ(n, render::unitSpaceNormal(in.normal, mesh.nominalSize));
            EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
            uint32_t rgba = 0;
            for (int c = 0; c < 4; ++c) rgba |= uint32_t(colours[4 * v + size_t(c)]) << (8 * c);
            EXPECT_EQ(rgba, in.rgba);
        }
    }
}

TEST(ShapeMeshGlb, AnEmptyMeshIsAValidFileWithoutGeometry) {
    render::TerminalMesh empty;
    empty.shape = "nothing";
    const std::vector<uint8_t> glb = shapeMeshGlb(empty, empty.shape);
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromMemory(&model, &err, &warn, glb.data(), unsigned(glb.size()))) << err;
    EXPECT_TRUE(model.meshes.empty());
    EXPECT_EQ(model.nodes.size(), 1u);
}

} // namespace
} // namespace hexlod::apps
