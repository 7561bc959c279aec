// Coarser meshes of the procedural shapes and the deviation that bounds what drawing one in
// place of its shape's mesh moves (mesh_deviation.h, buildCoarserProceduralMesh).
#include "hexlod/render/mesh_deviation.h"
#include "hexlod/render/procedural_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>

namespace hexlod::render {
namespace {

grammar::ShapeInfo treeShape(const std::string& name) {
    grammar::DiagnosticList diagnostics;
    const grammar::CompiledGrammar g =
        grammar::compileGrammarFile(std::string(HEXLOD_CONFIGS_DIR) + "/grammars/tree.grammar", diagnostics);
    const int index = g.findShape(name);
    EXPECT_GE(index, 0) << name << diagnostics.formatAll();
    return g.shapes.at(size_t(std::max(index, 0)));
}

// One triangle spanning the unit square's lower left half, at nominal size `nominal`.
TerminalMesh triangleMesh(glm::vec3 nominal, glm::vec3 offset = glm::vec3(0.0f)) {
    TerminalMesh mesh;
    mesh.nominalSize = nominal;
    for (const glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)})
        mesh.vertices.push_back({p + offset, glm::vec3(0, 0, 1), glm::vec2(0.0f), 0xffffffffu});
    mesh.indices = {0, 1, 2};
    return mesh;
}

TEST(MeshDeviation, IsZeroForTheSameMeshAndTheOffsetForAShiftedOne) {
    const TerminalMesh a = triangleMesh(glm::vec3(2.0f, 1.0f, 0.5f));
    EXPECT_EQ(meshDeviation(a, a), glm::vec3(0.0f));
    // Shifted out of its plane by a quarter of the depth: every sample moves exactly that far.
    const glm::vec3 out = meshDeviation(a, triangleMesh(a.nominalSize, glm::vec3(0, 0, 0.25f)));
    EXPECT_FLOAT_EQ(out.z, 0.25f);
    EXPECT_FLOAT_EQ(out.x, 0.0f);
    EXPECT_FLOAT_EQ(out.y, 0.0f);
    // Shifted along u within its plane: the overhanging corner (1.1, 0) is 0.1 beyond the other
    // triangle's reach along u, and the symmetric pass sees the uncovered corner (0, 0).
    const glm::vec3 along = meshDeviation(a, triangleMesh(a.nominalSize, glm::vec3(0.1f, 0, 0)));
    EXPECT_NEAR(along.x, 0.1f, 1e-5f);
    EXPECT_EQ(along.z, 0.0f);
}

TEST(MeshDeviation, IsMeasuredAtTheNominalSizeAndFlatAxesStayUnscaled) {
    // Nominal depth 0 (a flat tile): the t offset is reported as is, not divided by zero.
    const TerminalMesh flat = triangleMesh(glm::vec3(1.0f, 1.0f, 0.0f));
    const glm::vec3 d = meshDeviation(flat, triangleMesh(flat.nominalSize, glm::vec3(0, 0, 0.5f)));
    EXPECT_FLOAT_EQ(d.z, 0.5f);
    EXPECT_TRUE(std::isfinite(d.x) && std::isfinite(d.y));
}

TEST(MeshDeviation, AMeshWithoutTrianglesIsInfinitelyFarFromOneWith) {
    const TerminalMesh a = triangleMesh(glm::vec3(1.0f));
    TerminalMesh empty;
    EXPECT_TRUE(std::isinf(meshDeviation(a, empty).x));
    EXPECT_TRUE(std::isinf(meshDeviation(empty, a).y));
    EXPECT_EQ(meshDeviation(empty, empty), glm::vec3(0.0f));
}

// Two triangles side by side in the plane t = 0: [0, 0.5] x [0, 1] of colour `left` and
// [0.5, 1] x [0, 1] of colour `right`, with normal `normal`.
TerminalMesh twoPanels(uint32_t left, uint32_t right, glm::vec3 normal = glm::vec3(0, 0, 1)) {
    TerminalMesh mesh;
    mesh.nominalSize = glm::vec3(1.0f);
    for (const auto& [x0, colour] : {std::pair{0.0f, left}, std::pair{0.5f, right}}) {
        const uint32_t first = uint32_t(mesh.vertices.size());
        for (const glm::vec3 p : {glm::vec3(x0, 0, 0), glm::vec3(x0 + 0.5f, 0, 0), glm::vec3(x0, 1, 0)})
            mesh.vertices.push_back({p, normal, glm::vec2(0.0f), colour});
        mesh.indices.insert(mesh.indices.end(), {first, first + 1, first + 2});
    }
    return mesh;
}

TEST(MeshDeviation, MatchesOnlySurfaceOfTheSameColour) {
    const uint32_t red = packRgba(0.8f, 0.1f, 0.1f), grey = packRgba(0.5f, 0.5f, 0.5f);
    // The same shape, its panels' colours swapped: each panel's samples find their colour only
    // in the other panel, half the width away; a shift of 4 levels of 255 is still the same
    // colour.
    const glm::vec3 recoloured = meshDeviation(twoPanels(red, grey), twoPanels(grey, red));
    EXPECT_NEAR(recoloured.x, 0.5f, 1e-5f);
    EXPECT_EQ(recoloured.z, 0.0f);
    EXPECT_EQ(meshDeviation(twoPanels(red, grey), twoPanels(red, packRgba(0.5f, 0.5f, 0.5f + 4.0f / 255))),
              glm::vec3(0.0f));
    // A colour the other mesh lacks altogether: no surface to match, infinitely far.
    EXPECT_TRUE(std::isinf(meshDeviation(twoPanels(red, red), twoPanels(grey, grey)).x));
}

TEST(MeshDeviation, MatchesOnlySurfaceShadedAlike) {
    const uint32_t grey = packRgba(0.5f, 0.5f, 0.5f);
    const TerminalMesh facing = twoPanels(grey, grey);
    // Normals tilted by 30 degrees still match; by 60 degrees they shade differently.
    const float c30 = std::cos(0.5236f), s30 = std::sin(0.5236f);
    EXPECT_EQ(meshDeviation(facing, twoPanels(grey, grey, glm::vec3(s30, 0, c30))), glm::vec3(0.0f));
    EXPECT_TRUE(std::isinf(meshDeviation(facing, twoPanels(grey, grey, glm::vec3(c30, 0, s30))).y));
}

TEST(CoarserProceduralMesh, TreePartsGetTheirShareOfTheTrianglesWithinASmallDeviation) {
    // A fifth of the triangles (tree_meshes.cpp): the level nearest it.
    for (const auto& [name, share] : {std::pair{"leaf", 0.2f}, std::pair{"twig", 0.2f},
                                      std::pair{"bark", 0.2f}, std::pair{"fruit", 0.2f}}) {
        const grammar::ShapeInfo shape = treeShape(name);
        const TerminalMesh fine = buildProceduralMesh(shape).value();
        const std::optional<TerminalMesh> coarse = buildCoarserProceduralMesh(shape, fine);
        ASSERT_TRUE(coarse.has_value()) << name;
        const float ratio = float(coarse->triangleCount()) / float(fine.triangleCount());
        EXPECT_NEAR(ratio, share, 0.1f)
            << name << ": " << coarse->triangleCount() << " of " << fine.triangleCount();
        EXPECT_EQ(coarse->nominalSize, fine.nominalSize) << name;
        EXPECT_EQ(coarse->source, "procedural");
        const glm::vec3 deviation = meshDeviation(fine, *coarse);
        // Some change, and at most half the scope across the facade and up it (the twig's
        // three sides shade differently across nearly half of it, 2 cm of its 5; the leaf's
        // fold and curl are in t, which its depth of 1.5 cm turns into millimetres).
        EXPECT_GT(deviation.x + deviation.y + deviation.z, 0.0f) << name;
        EXPECT_LT(deviation.x, 0.5f) << name;
        EXPECT_LT(deviation.y, 0.3f) << name;
        EXPECT_LE(deviation.z, 1.0f) << name;
    }
}

TEST(CoarserProceduralMesh, NoneForAMeshNotFromAGeneratorOrWithoutACoarserLevel) {
    const grammar::ShapeInfo leaf = treeShape("leaf");
    TerminalMesh fine = buildProceduralMesh(leaf).value();
    fine.source = "models/leaf.glb";
    EXPECT_FALSE(buildCoarserProceduralMesh(leaf, fine).has_value());
    fine.source = "fallback";
    EXPECT_FALSE(buildCoarserProceduralMesh(leaf, fine).has_value());
    // Declared at the generator's coarsest level already: no level has its share of them.
    grammar::ShapeInfo least = leaf;
    least.triangles = 1;
    const TerminalMesh coarsest = buildProceduralMesh(least).value();
    EXPECT_FALSE(buildCoarserProceduralMesh(least, coarsest).has_value());
    grammar::ShapeInfo gizmo = leaf;
    gizmo.name = "gizmo";
    EXPECT_FALSE(buildCoarserProceduralMesh(gizmo, buildProceduralMesh(leaf).value()).has_value());
}

} // namespace
} // namespace hexlod::render
