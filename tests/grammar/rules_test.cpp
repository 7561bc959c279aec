// One test per rule of thesis Appendix A, with the expected scopes computed by hand.
// Every grammar restricts itself to atom 0 of a 20 m x 12 m lot: the south edge from
// (0, 0) to (20, 0), whose scope has x = east, y = up and z = south (outwards).
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

namespace hexlod::grammar {
namespace {

using test::compileOrFail;
using test::expandOne;
using test::rectangle;

constexpr float kTol = 1e-4f;
// Terminal sizes are stored as halves: 2^-11 relative precision (docs/grammar.md, Output).
float sizeTolerance(float size) {
    return std::max(kTol, size * 4.9e-4f);
}

const char* kShapes =
    "shape a(triangles = 2); shape b(triangles = 2); shape c(triangles = 2, depth_ratio = 0.5);\n";

std::vector<Terminal> run(const std::string& rules, const std::vector<ParameterOverride>& overrides = {},
                          uint32_t building = 0) {
    const std::string source = std::string(kShapes) + "Start -> Cond(atom == 0) { Go, NULL };\n" + rules;
    const CompiledGrammar g = compileOrFail(source);
    if (g.rules.empty()) return {};
    return expandOne(g, rectangle(20, 12), overrides, building).terminals;
}

void expectVec(glm::vec3 actual, glm::vec3 expected, float tol = kTol) {
    EXPECT_NEAR(actual.x, expected.x, tol) << "x";
    EXPECT_NEAR(actual.y, expected.y, tol) << "y";
    EXPECT_NEAR(actual.z, expected.z, tol) << "z";
}

TEST(Rules, ExtrudeAtomGivesAFaceAndTheRaisedAtom) {
    const auto t = run("Go -> Extrude(7) { Side, Top }; Side -> Shape(a); Top -> Shape(b);");
    ASSERT_EQ(t.size(), 2u);
    const Terminal& side = t[0].shape == 0 ? t[0] : t[1];
    const Terminal& top = t[0].shape == 1 ? t[0] : t[1];
    expectVec(side.position, {0, 0, 0});
    EXPECT_NEAR(side.size.x, 20, kTol);
    EXPECT_NEAR(side.size.y, 7, kTol);
    expectVec(side.axisX(), {1, 0, 0}, 1e-3f);
    expectVec(side.axisY(), {0, 0, 1}, 1e-3f);
    expectVec(side.normal(), {0, -1, 0}, 1e-3f);
    expectVec(top.position, {0, 0, 7});
    EXPECT_NEAR(top.size.x, 20, kTol);
    EXPECT_NEAR(top.size.y, 0, kTol);
}

TEST(Rules, ExtrudeScaleAndTwistActAboutTheAtomMiddle) {
    // Scale 0.5 leaves a 10 m atom centred on (10, 0, 7); a 90 degree twist about up turns
    // x from east to north, so the origin is the centre minus 5 m north.
    const auto t = run("Go -> Extrude(7, 0.5, 90) { NULL, Top }; Top -> Shape(b);");
    ASSERT_EQ(t.size(), 1u);
    expectVec(t[0].position, {10, -5, 7}, 1e-3f);
    EXPECT_NEAR(t[0].size.x, 10, kTol);
    expectVec(t[0].axisX(), {0, 1, 0}, 1e-3f);
    expectVec(t[0].normal(), {1, 0, 0}, 1e-3f);
}

TEST(Rules, ExtrudeFaceGivesABoxAndTheMovedFace) {
    // The 20 x 10 facade grows 2 m outwards (south): the top face sits at y = -2.
    const auto t =
        run("Go -> Extrude(10) { Face, NULL }; Face -> Extrude(2) { Box, Cap };"
            "Box -> Explode() { NULL, Front, NULL, NULL, NULL }; Front -> Shape(a); Cap -> Shape(b);");
    ASSERT_EQ(t.size(), 2u);
    for (const Terminal& terminal : t) {
        // The box's front face and the extrusion's cap coincide.
        expectVec(terminal.position, {0, -2, 0});
        EXPECT_NEAR(terminal.size.x, 20, kTol);
        EXPECT_NEAR(terminal.size.y, 10, kTol);
        expectVec(terminal.normal(), {0, -1, 0}, 1e-3f);
    }
}

TEST(Rules, SplitSharesTheRemainderAmongRelativeParts) {
    // On 20 m: absolute 2 and 3 leave 15 for ~1 and ~2: parts 2, 5, 3, 10 at 0, 2, 7, 10.
    const auto t =
        run("Go -> Extrude(4) { F, NULL }; F -> Split(x, 2, ~1, 3, ~2) { A, A, A, A }; A -> Shape(a);");
    ASSERT_EQ(t.size(), 4u);
    const float expectedX[] = {0, 2, 7, 10}, expectedW[] = {2, 5, 3, 10};
    for (int i = 0; i < 4; ++i) {
        expectVec(t[i].position, {expectedX[i], 0, 0});
        EXPECT_NEAR(t[i].size.x, expectedW[i], kTol);
        EXPECT_NEAR(t[i].size.y, 4, kTol);
    }
}

TEST(Rules, SplitScalesOverflowingAbsolutePartsAndDropsEmptyOnes) {
    // 15 + 10 overflow 20 m: scaled by 0.8 to 12 and 8; the ~1 part gets 0 and is dropped.
    const auto t =
        run("Go -> Extrude(4) { F, NULL }; F -> Split(x, 15, 10, ~1) { A, A, B }; A -> Shape(a); B -> "
            "Shape(b);");
    ASSERT_EQ(t.size(), 2u);
    EXPECT_NEAR(t[0].size.x, 12, kTol);
    EXPECT_NEAR(t[1].size.x, 8, kTol);
    expectVec(t[1].position, {12, 0, 0});
}

TEST(Rules, SplitAlongYSetsTheFloorIndex) {
    // Floors of 3, 3 and the rest (4 m) of a 10 m facade; the top one emits shape b.
    const auto t = run("Go -> Extrude(10) { F, NULL }; F -> Split(y, 3, 3, ~1) { L, L, L };"
                       "L -> Cond(floor == 2 && floor_count == 3) { B, A }; A -> Shape(a); B -> Shape(b);");
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t[2].shape, 1);
    expectVec(t[2].position, {0, 0, 6});
    EXPECT_NEAR(t[2].size.y, 4, kTol);
}

TEST(Rules, RepeatFitPlacesExactTilesWithCentredMargins) {
    // 20 m / 3 m: 6 tiles of exactly 3 m, 1 m margins at both ends going to M.
    const auto t =
        run("Go -> Extrude(4) { F, NULL }; F -> Repeat(x, 3, fit) { T, M }; T -> Shape(a); M -> Shape(b);");
    ASSERT_EQ(t.size(), 8u);
    std::vector<float> tiles, margins;
    for (const Terminal& terminal : t) {
        (terminal.shape == 0 ? tiles : margins).push_back(terminal.position.x);
        EXPECT_NEAR(terminal.size.x, terminal.shape == 0 ? 3.0f : 1.0f, kTol);
    }
    ASSERT_EQ(tiles.size(), 6u);
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(tiles[i], 1.0f + 3.0f * i, kTol);
    ASSERT_EQ(margins.size(), 2u);
    EXPECT_NEAR(margins[0], 0.0f, kTol);
    EXPECT_NEAR(margins[1], 19.0f, kTol);
}

TEST(Rules, RepeatEqualFillsTheScope) {
    // round(20 / 3) = 7 tiles of 20/7 m.
    const auto t = run("Go -> Extrude(4) { F, NULL }; F -> Repeat(x, 3, equal) { T }; T -> Shape(a);");
    ASSERT_EQ(t.size(), 7u);
    for (int i = 0; i < 7; ++i) {
        EXPECT_NEAR(t[i].size.x, 20.0f / 7.0f, sizeTolerance(20.0f / 7.0f));
        EXPECT_NEAR(t[i].position.x, 20.0f / 7.0f * i, 1e-3f);
    }
}

TEST(Rules, RepeatIndexAndCountAreReadable) {
    // Only the last of the 7 tiles passes the condition.
    const auto t =
        run("Go -> Extrude(4) { F, NULL }; F -> Repeat(x, 3, equal) { T }; T -> Cond(index == count - 1) "
            "{ A, NULL }; A -> Shape(a);");
    ASSERT_EQ(t.size(), 1u);
    EXPECT_NEAR(t[0].position.x, 120.0f / 7.0f, 1e-3f);
}

TEST(Rules, BranchCopiesTheScopeWithIndexAndLevel) {
    const auto t =
        run("Go -> Extrude(4) { F, NULL }; F -> Branch(3) { C }; C -> Cond(level == 1) { P, NULL };"
            "P -> Translate(index * 5, 0, 0) { A }; A -> Shape(a);");
    ASSERT_EQ(t.size(), 3u);
    for (int i = 0; i < 3; ++i) expectVec(t[i].position, {5.0f * i, 0, 0});
}

TEST(Rules, BranchWithOneSuccessorPerCopy) {
    const auto t =
        run("Go -> Extrude(4) { F, NULL }; F -> Branch(2) { A, B }; A -> Shape(a); B -> Shape(b);");
    ASSERT_EQ(t.size(), 2u);
    EXPECT_EQ(t[0].shape, 0);
    EXPECT_EQ(t[1].shape, 1);
}

TEST(Rules, TranslateMovesAlongTheScopeAxes) {
    // x east 1, y up 2, z south 3.
    const auto t = run("Go -> Extrude(4) { F, NULL }; F -> Translate(1, 2, 3) { A }; A -> Shape(a);");
    ASSERT_EQ(t.size(), 1u);
    expectVec(t[0].position, {1, -3, 2});
}

TEST(Rules, RotateAboutTheOriginCorner) {
    // 90 degrees about the scope's y (up): x turns from east to north, z from south to east.
    const auto t = run("Go -> Extrude(4) { F, NULL }; F -> Rotate(origin, y, 90) { A }; A -> Shape(a);");
    ASSERT_EQ(t.size(), 1u);
    expectVec(t[0].position, {0, 0, 0});
    expectVec(t[0].axisX(), {0, 1, 0}, 1e-3f);
    expectVec(t[0].normal(), {1, 0, 0}, 1e-3f);
}

TEST(Rules, RotateAboutTheCentre) {
    // The face's centre (10, 0, 2) stays; the origin corner (0, 0, 0) swings to (10, -10, 0).
    const auto t = run("Go -> Extrude(4) { F, NULL }; F -> Rotate(center, y, 90) { A }; A -> Shape(a);");
    ASSERT_EQ(t.size(), 1u);
    expectVec(t[0].position, {10, -10, 0}, 1e-3f);
}

TEST(Rules, CondPicksThenOrElse) {
    const auto t = run("Go -> Extrude(4) { F, NULL }; F -> Repeat(x, 5, equal) { T };"
                       "T -> Cond(index % 2 == 0) { A, B }; A -> Shape(a); B -> Shape(b);");
    ASSERT_EQ(t.size(), 4u);
    EXPECT_EQ(t[0].shape, 0);
    EXPECT_EQ(t[1].shape, 1);
    EXPECT_EQ(t[2].shape, 0);
    EXPECT_EQ(t[3].shape, 1);
}

TEST(Rules, ShapeUsesTheDeclaredOrTheGivenDepthRatio) {
    const auto t = run("Go -> Extrude(4) { F, G }; F -> Shape(c); G -> Shape(c, 0.25);");
    ASSERT_EQ(t.size(), 2u);
    EXPECT_NEAR(t[0].depthRatio, 0.5f, 1e-3f);
    EXPECT_NEAR(t[1].depthRatio, 0.25f, 1e-3f);
}

TEST(Rules, ExplodeGivesOutwardFacingFaces) {
    // A 20 x 10 facade extruded 2 m outwards (south) is a box; its faces, each facing out.
    const auto t = run("Go -> Extrude(10) { F, NULL }; F -> Extrude(2) { Box, NULL };"
                       "Box -> Explode() { A, A, A, A, A }; A -> Shape(a);");
    ASSERT_EQ(t.size(), 5u);
    // left, front, right, back, top
    const glm::vec3 normals[5] = {{-1, 0, 0}, {0, -1, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const glm::vec2 sizes[5] = {{2, 10}, {20, 10}, {2, 10}, {20, 10}, {20, 2}};
    const glm::vec3 origins[5] = {{0, 0, 0}, {0, -2, 0}, {20, -2, 0}, {20, 0, 0}, {0, -2, 10}};
    for (int i = 0; i < 5; ++i) {
        expectVec(t[i].normal(), normals[i], 1e-3f);
        EXPECT_NEAR(t[i].size.x, sizes[i].x, kTol);
        EXPECT_NEAR(t[i].size.y, sizes[i].y, kTol);
        expectVec(t[i].position, origins[i], 1e-3f);
    }
}

TEST(Rules, ProjectReorientsTheScope) {
    // Project(y, x): x becomes up, y becomes east, z = up x east = north (inwards).
    const auto t = run("Go -> Extrude(4) { F, NULL }; F -> Project(y, x) { A }; A -> Shape(a);");
    ASSERT_EQ(t.size(), 1u);
    EXPECT_NEAR(t[0].size.x, 4, kTol);
    EXPECT_NEAR(t[0].size.y, 20, kTol);
    expectVec(t[0].axisX(), {0, 0, 1}, 1e-3f);
    expectVec(t[0].axisY(), {1, 0, 0}, 1e-3f);
    expectVec(t[0].normal(), {0, 1, 0}, 1e-3f);
}

TEST(Rules, NullDropsTheScope) {
    EXPECT_TRUE(run("Go -> Extrude(4) { Nothing, NULL }; Nothing -> NULL;").empty());
}

TEST(Rules, ChooseFollowsItsProbabilities) {
    // 4000 tiles of 0.005 m: about a quarter pick A.
    const auto t = run("Go -> Extrude(1) { F, NULL }; F -> Repeat(x, 0.005, equal) { T };"
                       "T -> Choose(1: A, 3: B); A -> Shape(a); B -> Shape(b);");
    ASSERT_EQ(t.size(), 4000u);
    size_t a = 0;
    for (const Terminal& terminal : t) a += terminal.shape == 0;
    EXPECT_NEAR(double(a) / 4000.0, 0.25, 0.03);
}

TEST(Rules, ChooseIsKeyedByBuildingAndPosition) {
    const std::string rules = "Go -> Extrude(1) { F, NULL }; F -> Repeat(x, 0.5, equal) { T };"
                              "T -> Choose(1: A, 1: B); A -> Shape(a); B -> Shape(b);";
    auto shapes = [](const std::vector<Terminal>& t) {
        std::string s;
        for (const Terminal& terminal : t) s += char('a' + terminal.shape);
        return s;
    };
    const std::string first = shapes(run(rules, {}, 7));
    EXPECT_EQ(first, shapes(run(rules, {}, 7)));
    EXPECT_NE(first, shapes(run(rules, {}, 8)));
}

TEST(Rules, ParametersAndAccessorsFeedExpressions) {
    const auto t = run("param h = 5 in [1, 50];\nGo -> Extrude(h * 2) { F, NULL };"
                       "F -> Extrude(max(width, height) / 4 + elevation) { NULL, Cap }; Cap -> Shape(a);",
                       {{"h", 3}});
    // height 6, width 20: the cap moves out by 20 / 4 = 5 m.
    ASSERT_EQ(t.size(), 1u);
    EXPECT_NEAR(t[0].size.y, 6, kTol);
    expectVec(t[0].position, {0, -5, 0});
}

TEST(Rules, RandIsDeterministicAndInRange) {
    const std::string rules = "Go -> Extrude(rand(2, 4)) { F, NULL }; F -> Shape(a);";
    const auto first = run(rules), second = run(rules);
    ASSERT_EQ(first.size(), 1u);
    EXPECT_GE(first[0].size.y, 2.0f);
    EXPECT_LT(first[0].size.y, 4.0f);
    EXPECT_EQ(first[0].size.y, second[0].size.y);
}

TEST(Rules, WorldNormalIgnoresRotation) {
    const auto t = run("Go -> Extrude(4) { F, NULL }; F -> Rotate(origin, y, 90) { R };"
                       "R -> Cond(world_normal_y < -0.9 && normal_x > 0.9) { A, NULL }; A -> Shape(a);");
    EXPECT_EQ(t.size(), 1u);
}

} // namespace
} // namespace hexlod::grammar

namespace hexlod::grammar {
namespace {

TEST(Rules, BuildingRandIsOneValuePerBuildingAndStream) {
    // Every tile of every edge reads stream 1: all tiles of one building pick alike.
    const std::string source = std::string(kShapes) +
                               "Go -> Extrude(4) { F, NULL }; F -> Repeat(x, 1, equal) { T };"
                               "T -> Cond(building_rand(1) < 0.5) { A, B }; A -> Shape(a); B -> Shape(b);";
    const CompiledGrammar g = compileOrFail(source);
    std::set<uint16_t> shapesSeen;
    for (uint32_t building = 0; building < 16; ++building) {
        const auto t = expandOne(g, rectangle(20, 12), {}, building).terminals;
        ASSERT_EQ(t.size(), 64u);
        std::set<uint16_t> shapes;
        for (const Terminal& terminal : t) shapes.insert(terminal.shape);
        EXPECT_EQ(shapes.size(), 1u) << "building " << building;
        shapesSeen.insert(shapes.begin(), shapes.end());
    }
    EXPECT_EQ(shapesSeen.size(), 2u); // and buildings differ
}

TEST(Rules, AddingOrReorderingRulesKeepsRandomPicks) {
    const std::string rules = "Go -> Extrude(rand(3, 9)) { F, NULL }; F -> Repeat(x, 0.5, equal) { T };"
                              "T -> Choose(1: A, 1: B); A -> Shape(a); B -> Shape(b);";
    const std::string reordered = "Go -> Extrude(rand(3, 9)) { F, NULL }; Extra -> Shape(c);"
                                  "B -> Shape(b); T -> Choose(1: A, 1: B); A -> Shape(a);"
                                  "F -> Repeat(x, 0.5, equal) { T };";
    const auto before = run(rules), after = run(reordered);
    ASSERT_EQ(before.size(), after.size());
    for (size_t i = 0; i < before.size(); ++i) {
        EXPECT_EQ(before[i].shape, after[i].shape) << i;
        EXPECT_EQ(before[i].size.y, after[i].size.y) << i;
    }
}

TEST(Rules, UnusedShapesAndParametersAreWarnings) {
    const std::string errors = test::compileErrors("param used = 1 in [0, 2];\nparam spare = 1 in [0, 2];\n"
                                                   "shape a(triangles = 2);\nshape b(triangles = 2);\n"
                                                   "A -> Extrude(used) { S, NULL }; S -> Shape(a);");
    EXPECT_EQ(errors, "test.grammar:2:7: warning: parameter 'spare' is declared but never read\n"
                      "test.grammar:4:7: warning: shape 'b' is declared but no rule emits it\n");
}

} // namespace
} // namespace hexlod::grammar
