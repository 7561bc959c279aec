// Every procedural terminal mesh of the shipped grammars against the unit-scope-space contract
// (render/include/hexlod/render/terminal_mesh.h) and the grammars' triangle declarations, plus
// hand-checked geometry facts about individual shapes.
#include "hexlod/render/procedural_meshes.h"
#include "hexlod/render/terminal_mesh_library.h"
#include "mesh_builder.h"
#include "shape_generators.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace hexlod::render {
namespace {

constexpr const char* kShippedGrammars[] = {"residential", "business", "thesis-example", "tree"};

grammar::CompiledGrammar loadGrammar(const std::string& name) {
    grammar::DiagnosticList diagnostics;
    grammar::CompiledGrammar g = grammar::compileGrammarFile(
        std::string(HEXLOD_CONFIGS_DIR) + "/grammars/" + name + ".grammar", diagnostics);
    EXPECT_FALSE(g.rules.empty()) << diagnostics.formatAll();
    return g;
}

const grammar::ShapeInfo& shapeOf(const grammar::CompiledGrammar& g, const std::string& name) {
    const int index = g.findShape(name);
    EXPECT_GE(index, 0) << name;
    return g.shapes.at(size_t(std::max(index, 0)));
}

TerminalMesh meshOf(const std::string& grammar, const std::string& shape) {
    const grammar::CompiledGrammar g = loadGrammar(grammar);
    std::optional<TerminalMesh> mesh = buildProceduralMesh(shapeOf(g, shape));
    EXPECT_TRUE(mesh.has_value()) << shape;
    return mesh.value_or(TerminalMesh{});
}

// Metric area of a triangle at the nominal size.
float nominalArea(const TerminalMesh& m, size_t t) {
    const glm::vec3 s = m.nominalSize;
    const glm::vec3 a = m.vertices[m.indices[t]].position * s, b = m.vertices[m.indices[t + 1]].position * s,
                    c = m.vertices[m.indices[t + 2]].position * s;
    return 0.5f * glm::length(glm::cross(b - a, c - a));
}

TEST(ProceduralMeshes, EveryShippedShapeHasAGenerator) {
    const std::vector<std::string> names = proceduralShapeNames();
    for (const char* grammar : kShippedGrammars) {
        for (const grammar::ShapeInfo& s : loadGrammar(grammar).shapes)
            EXPECT_TRUE(std::binary_search(names.begin(), names.end(), s.name)) << grammar << " " << s.name;
    }
}

// The library stops its search for the declared triangle count at the first level that reaches
// it, which is only right if no generator loses triangles as its detail grows.
TEST(ProceduralMeshes, DetailLevelsNeverLoseTriangles) {
    for (const auto family :
         {windowGenerators(), facadeGenerators(), towerGenerators(), roofGenerators(), treeGenerators()}) {
        for (const ShapeGenerator& g : family) {
            size_t previous = 0;
            for (int detail = 0; detail <= g.maxDetail; ++detail) {
                MeshBuilder b(glm::vec3(1.5f, 2.0f, 0.3f));
                g.build(b, detail);
                EXPECT_GE(b.triangleCount(), previous) << g.name << " detail " << detail;
                previous = b.triangleCount();
            }
        }
    }
}

TEST(ProceduralMeshes, MeetTheUnitScopeContractAndTheirDeclarations) {
    for (const char* grammar : kShippedGrammars) {
        const grammar::CompiledGrammar g = loadGrammar(grammar);
        for (const grammar::ShapeInfo& s : g.shapes) {
            SCOPED_TRACE(std::string(grammar) + " " + s.name);
            const TerminalMesh m = buildProceduralMesh(s).value();
            EXPECT_EQ(m.shape, s.name);
            EXPECT_EQ(m.source, "procedural");
            ASSERT_EQ(m.indices.size() % 3, 0u);
            const size_t triangles = m.triangleCount();
            std::printf("  %-16s %-16s %4zu triangles (declared %4u), %5zu vertices, %6zu bytes\n", grammar,
                        s.name.c_str(), triangles, s.triangles, m.vertices.size(), m.byteSize());
            const bool flat = s.depthRatio == 0.0f;
            if (flat) {
                EXPECT_EQ(triangles, 2u) << "a shape of depth 0 is one flat quad";
            } else {
                EXPECT_GE(triangles, 50u);
                EXPECT_LE(triangles, 500u);
            }
            EXPECT_LE(std::abs(double(triangles) - double(s.triangles)), 0.1 * double(s.triangles))
                << "declared " << s.triangles;
            for (const uint32_t i : m.indices) ASSERT_LT(i, m.vertices.size());
            for (const MeshVertex& v : m.vertices) {
                for (int k = 0; k < 3; ++k) {
                    ASSERT_TRUE(std::isfinite(v.position[k]) && std::isfinite(v.normal[k]));
                }
                EXPECT_GE(v.position.x, -1e-5f);
                EXPECT_LE(v.position.x, 1.0f + 1e-5f);
                EXPECT_GE(v.position.y, -1e-5f);
                EXPECT_LE(v.position.y, 1.0f + 1e-5f);
                EXPECT_GE(v.position.z, -1.0f - 1e-5f);
                EXPECT_LE(v.position.z, 1.0f + 1e-5f);
                if (flat) {
                    EXPECT_EQ(v.position.z, 0.0f);
                }
                EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-4f);
                EXPECT_TRUE(std::isfinite(v.uv.x) && std::isfinite(v.uv.y));
            }
            for (size_t t = 0; t < m.indices.size(); t += 3)
                EXPECT_GT(nominalArea(m, t), 1e-9f) << "triangle " << t / 3;
            EXPECT_EQ(m.nominalSize, nominalShapeSize(s.width, s.height, s.depthRatio));
        }
    }
}

// Flat-shaded faces: the normal the contract carries to any stretched scope stays
// perpendicular to the stretched triangle, and faces the way its winding says.
TEST(ProceduralMeshes, NormalsFollowTheScopeStretch) {
    const TerminalMesh m = meshOf("residential", "balcony");
    for (const glm::vec3 scope :
         {glm::vec3(2.8f, 1.05f, 1.155f), glm::vec3(7.0f, 0.8f, 0.3f), glm::vec3(1, 3, 2)}) {
        size_t flatFaces = 0;
        for (size_t t = 0; t < m.indices.size(); t += 3) {
            const MeshVertex &a = m.vertices[m.indices[t]], &b = m.vertices[m.indices[t + 1]],
                             &c = m.vertices[m.indices[t + 2]];
            if (a.normal != b.normal || a.normal != c.normal) continue;
            ++flatFaces;
            const glm::vec3 e0 = (b.position - a.position) * scope, e1 = (c.position - a.position) * scope;
            const glm::vec3 geometric = glm::normalize(glm::cross(e0, e1));
            const glm::vec3 n = scopeNormal(a.normal, m.nominalSize, scope);
            EXPECT_NEAR(glm::dot(n, geometric), 1.0f, 1e-3f) << "triangle " << t / 3;
            const glm::vec3 viaUnit = glm::normalize(unitSpaceNormal(a.normal, m.nominalSize) / scope);
            EXPECT_NEAR(glm::dot(viaUnit, n), 1.0f, 1e-5f);
        }
        EXPECT_GT(flatFaces, m.triangleCount() / 2);
    }
}

TEST(ProceduralMeshes, HashesAreDeterministicAndTellShapesApart) {
    std::set<uint64_t> hashes;
    size_t meshes = 0;
    for (const char* grammar : {"residential", "business", "tree"}) {
        for (const grammar::ShapeInfo& s : loadGrammar(grammar).shapes) {
            const uint64_t first = buildProceduralMesh(s)->contentHash;
            EXPECT_EQ(first, buildProceduralMesh(s)->contentHash) << s.name;
            hashes.insert(first);
            ++meshes;
        }
    }
    EXPECT_EQ(hashes.size(), meshes);
}

TEST(ProceduralMeshes, SameNameFollowsEachGrammarsDeclaration) {
    // `door` is declared with 180 triangles in residential and 120 in the thesis example.
    const TerminalMesh residential = meshOf("residential", "door"), thesis = meshOf("thesis-example", "door");
    EXPECT_NEAR(double(residential.triangleCount()), 180.0, 18.0);
    EXPECT_NEAR(double(thesis.triangleCount()), 120.0, 12.0);
    EXPECT_NE(residential.contentHash, thesis.contentHash);
}

float maxT(const TerminalMesh& m, uint32_t rgba = 0) {
    float t = -2.0f;
    for (const MeshVertex& v : m.vertices) {
        if (rgba == 0 || v.rgba == rgba) t = std::max(t, v.position.z);
    }
    return t;
}

TEST(ProceduralMeshes, WindowGlassIsRecessedAndSurroundsStandOut) {
    for (const char* shape :
         {"window_casement", "window_sash", "window_arched", "balcony_door", "shop_window"}) {
        const TerminalMesh m = meshOf("residential", shape);
        size_t glass = 0;
        for (const MeshVertex& v : m.vertices) {
            if (v.rgba != palette::kGlass) continue;
            ++glass;
            EXPECT_LT(v.position.z, -0.2f) << shape;
        }
        EXPECT_GT(glass, 3u) << shape;
        EXPECT_GT(maxT(m), 0.3f) << shape << ": the surround stands out of the wall";
    }
    const TerminalMesh sill = meshOf("residential", "window_sill");
    EXPECT_GT(maxT(sill), 0.95f);
}

TEST(ProceduralMeshes, ArchedWindowHasACurvedHead) {
    const TerminalMesh m = meshOf("residential", "window_arched");
    // The glass reaches the top of the scope only in the middle.
    float topAtMiddle = 0.0f, topAtSide = 0.0f;
    for (const MeshVertex& v : m.vertices) {
        if (v.rgba != palette::kGlass) continue;
        if (std::abs(v.position.x - 0.5f) < 0.1f) topAtMiddle = std::max(topAtMiddle, v.position.y);
        if (v.position.x < 0.2f) topAtSide = std::max(topAtSide, v.position.y);
    }
    EXPECT_GT(topAtMiddle, 0.85f);
    EXPECT_LT(topAtSide, topAtMiddle - 0.1f);
}

TEST(ProceduralMeshes, BalconyHasARailingAboveItsSlab) {
    const TerminalMesh m = meshOf("residential", "balcony");
    size_t railing = 0;
    float slabTop = 0.0f;
    for (const MeshVertex& v : m.vertices) {
        if (v.rgba == palette::kLightStone) slabTop = std::max(slabTop, v.position.y);
        if (v.rgba == palette::kDarkMetal && v.position.y > 0.5f && v.position.z > 0.8f) ++railing;
    }
    EXPECT_LT(slabTop, 0.2f);
    EXPECT_GT(railing, 40u); // balusters and the top rail
}

TEST(ProceduralMeshes, TreePartsSitWhereTheGrowthGrammarPutsThem) {
    const TerminalMesh bark = meshOf("tree", "bark");
    glm::vec3 centre(0.0f);
    for (const MeshVertex& v : bark.vertices) centre += v.position;
    centre /= float(bark.vertices.size());
    EXPECT_NEAR(centre.x, 0.5f, 0.02f);
    EXPECT_NEAR(centre.z, 0.0f, 0.02f);
    EXPECT_LT(bark.boundsMin.y, 1e-6f);
    EXPECT_GT(bark.boundsMax.y, 1.0f - 1e-6f);
    // Leaves are seen from both sides: every face has a twin facing the other way.
    const TerminalMesh leaf = meshOf("tree", "leaf");
    size_t up = 0, down = 0;
    for (const MeshVertex& v : leaf.vertices) (v.normal.z >= 0.0f ? up : down) += 1;
    EXPECT_EQ(up, down);
    const TerminalMesh fruit = meshOf("tree", "fruit");
    EXPECT_NEAR(fruit.boundsMax.z, -fruit.boundsMin.z, 1e-5f);
}

TEST(ProceduralMeshes, TerraceRailingStandsOnTheOuterEdge) {
    // Terrace decks are emitted with z up and y pointing into the building: the balustrade
    // stands near y = 0 and rises to near t = 1.
    const TerminalMesh m = meshOf("business", "terrace_deck");
    float railTop = 0.0f;
    for (const MeshVertex& v : m.vertices) {
        if (v.rgba == palette::kSteel && v.position.y < 0.1f) railTop = std::max(railTop, v.position.z);
    }
    EXPECT_GT(railTop, 0.85f);
}

TEST(ProceduralMeshes, UnknownShapesGetAFallbackBox) {
    grammar::ShapeInfo gizmo;
    gizmo.name = "gizmo";
    gizmo.depthRatio = 0.5f;
    gizmo.triangles = 40;
    EXPECT_FALSE(buildProceduralMesh(gizmo).has_value());
    const TerminalMesh box = buildFallbackMesh(gizmo);
    EXPECT_EQ(box.triangleCount(), 12u);
    EXPECT_EQ(box.source, "fallback");
    EXPECT_EQ(box.boundsMin, glm::vec3(0.0f));
    EXPECT_EQ(box.boundsMax, glm::vec3(1.0f));
    for (const MeshVertex& v : box.vertices) EXPECT_EQ(v.rgba, palette::kFallback);
}

} // namespace
} // namespace hexlod::render
