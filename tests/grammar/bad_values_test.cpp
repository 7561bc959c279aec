// Run-time robustness: bad parameter values, degenerate footprints, NaN and out-of-range
// sizes and runaway derivations must end quickly with the documented IssueKind (or the
// documented clean-up), never with a hang, a crash or silently wrong output.
#include "test_support.h"

#include "hexlod/grammar/batch_expander.h"
#include "hexlod/grammar/compiled_grammar.h"
#include "hexlod/grammar/expander.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace hexlod::grammar {
namespace {

using hexlod::test::compileOrFail;
using hexlod::test::countByShape;
using hexlod::test::expandOne;
using hexlod::test::Expansion;
using hexlod::test::rectangle;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Caps must turn runaway grammars into diagnostics, never hangs. The bound only tells a hang
// from slow work; it is far above the milliseconds these take, so sanitizers and a loaded
// machine do not make it flaky (speed itself is measured in benchmarks, not here).
constexpr double kNotAHangSeconds = 30.0;

// Runs `body` and returns its wall time in seconds.
template <typename Body> double secondsFor(Body&& body) {
    const auto start = std::chrono::steady_clock::now();
    body();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<const ExpansionIssue*> issuesOf(const BuildingOutput& out, IssueKind kind) {
    std::vector<const ExpansionIssue*> found;
    for (const ExpansionIssue& issue : out.issues) {
        if (issue.kind == kind) found.push_back(&issue);
    }
    return found;
}

std::string ruleOf(const CompiledGrammar& g, const ExpansionIssue& issue) {
    return issue.rule == kNullRule ? "<none>" : g.ruleNames.at(issue.rule);
}

std::string describeAll(const CompiledGrammar& g, const BuildingOutput& out) {
    std::string text;
    for (const ExpansionIssue& issue : out.issues) text += describeIssue(g, issue) + "\n";
    return text;
}

// --- Parameters ----------------------------------------------------------------------

constexpr const char* kParameterGrammar = "param floor_h = 3 in [2.5, 6];\n"
                                          "param floors = 2 in [1, 40];\n"
                                          "shape wall(triangles = 2);\n"
                                          "Lot -> Extrude(floors * floor_h) { Wall, NULL };\n"
                                          "Wall -> Shape(wall);\n";

struct BadOverride {
    const char* name;
    ParameterOverride override;
    const char* message; // substring of the error; every message names the parameter
};

TEST(BadParameterValuesTest, ResolveParametersRejectsAndKeepsTheDefault) {
    const CompiledGrammar g = compileOrFail(kParameterGrammar, "params.grammar");
    const BadOverride cases[] = {
        {"NaN", {"floor_h", kNaN}, "parameter 'floor_h' must be a finite number"},
        {"+Inf", {"floor_h", kInf}, "parameter 'floor_h' must be a finite number"},
        {"-Inf", {"floors", -kInf}, "parameter 'floors' must be a finite number"},
        {"above the range", {"floor_h", 6.5}, "parameter 'floor_h' = 6.5 is outside its range [2.5, 6]"},
        {"below the range", {"floors", 0.0}, "parameter 'floors' = 0 is outside its range [1, 40]"},
        {"unknown name", {"flor_h", 3.0}, "unknown parameter 'flor_h'"},
    };
    for (const BadOverride& c : cases) {
        DiagnosticList diagnostics;
        const std::vector<float> values = resolveParameters(g, {c.override}, diagnostics);
        ASSERT_EQ(diagnostics.all().size(), 1u) << c.name;
        EXPECT_EQ(diagnostics.all()[0].severity, Severity::Error) << c.name;
        EXPECT_NE(diagnostics.all()[0].message.find(c.message), std::string::npos)
            << c.name << ": " << diagnostics.all()[0].message;
        EXPECT_EQ(values, (std::vector<float>{3.0f, 2.0f})) << c.name;
    }
}

TEST(BadParameterValuesTest, GoodOverridesNextToABadOneStillApply) {
    const CompiledGrammar g = compileOrFail(kParameterGrammar, "params.grammar");
    DiagnosticList diagnostics;
    const std::vector<float> values =
        resolveParameters(g, {{"floors", 40.0}, {"floor_h", kNaN}, {"floor_h", 2.5}}, diagnostics);
    EXPECT_EQ(diagnostics.all().size(), 1u) << diagnostics.formatAll();
    EXPECT_EQ(values, (std::vector<float>{2.5f, 40.0f}));
}

TEST(BadParameterValuesTest, WrongSizedParameterVectorFallsBackToDefaults) {
    const CompiledGrammar g = compileOrFail(kParameterGrammar, "params.grammar");
    ExpansionSettings settings;
    settings.seed = 1;
    BuildingExpander expander(g, settings);
    BuildingInput input;
    input.footprint = rectangle(10, 8);
    input.parameters = {4.0f}; // one value for a grammar with two parameters
    BuildingOutput out;
    expander.expand(input, out);
    ASSERT_EQ(out.issues.size(), 1u) << describeAll(g, out);
    EXPECT_EQ(out.issues[0].kind, IssueKind::BadParameters);
    EXPECT_FALSE(issueIsError(IssueKind::BadParameters));
    ASSERT_EQ(out.terminals.size(), 4u);
    // The default height 2 * 3 m, not anything derived from the stray 4.
    EXPECT_FLOAT_EQ(unpackTerminal(out.terminals[0]).size.y, 6.0f);
}

// --- Footprints ----------------------------------------------------------------------

constexpr const char* kWallGrammar = "shape wall(triangles = 2);\n"
                                     "Lot -> Extrude(3) { Wall, NULL };\n"
                                     "Wall -> Shape(wall);\n";

struct BadFootprint {
    const char* name;
    std::vector<glm::dvec2> points;
    const char* detail; // substring of the DegenerateFootprint detail
};

TEST(BadFootprintTest, UnusableFootprintsSkipTheBuilding) {
    const CompiledGrammar g = compileOrFail(kWallGrammar, "walls.grammar");
    const BadFootprint cases[] = {
        {"empty", {}, "footprint is empty"},
        {"two distinct points",
         {{0, 0}, {5, 0}, {5, 0}, {0, 0}},
         "fewer than 3 distinct, non-collinear points"},
        {"all collinear", {{0, 0}, {1, 0}, {2, 0}, {5, 0}}, "fewer than 3 distinct, non-collinear points"},
        {"collinear there and back",
         {{0, 0}, {5, 5}, {10, 10}, {5, 5}},
         "fewer than 3 distinct, non-collinear points"},
        // A symmetric bow-tie: both lobes cancel, so its signed area is exactly 0.
        {"zero area", {{0, 0}, {2, 2}, {2, 0}, {0, 2}}, "footprint has zero area"},
        {"NaN coordinate", {{0, 0}, {kNaN, 0}, {5, 5}, {0, 5}}, "non-finite coordinate"},
        {"infinite coordinate", {{0, 0}, {5, 0}, {5, kInf}, {0, 5}}, "non-finite coordinate"},
    };
    for (const BadFootprint& c : cases) {
        const Expansion e = expandOne(g, c.points, {}, 42);
        EXPECT_TRUE(e.output.skipped) << c.name;
        EXPECT_TRUE(e.output.terminals.empty()) << c.name;
        EXPECT_TRUE(e.output.elements.empty()) << c.name;
        EXPECT_EQ(e.output.atoms, 0u) << c.name;
        ASSERT_EQ(e.output.issues.size(), 1u) << c.name << "\n" << describeAll(g, e.output);
        const ExpansionIssue& issue = e.output.issues[0];
        EXPECT_EQ(issue.kind, IssueKind::DegenerateFootprint) << c.name;
        EXPECT_EQ(issue.rule, kNullRule) << c.name;
        EXPECT_EQ(issue.building, 42u) << c.name;
        EXPECT_NE(issue.detail.find(c.detail), std::string::npos) << c.name << ": " << issue.detail;
        EXPECT_TRUE(issueIsError(issue.kind));
    }
}

TEST(BadFootprintTest, DuplicateAndCollinearPointsCleanUpToTheRectangle) {
    const CompiledGrammar g = compileOrFail(kWallGrammar, "walls.grammar");
    // Repeated points, a collinear point in the middle of the first edge and the closing point.
    const Expansion e =
        expandOne(g, {{0, 0}, {0, 0}, {5, 0}, {10, 0}, {10, 0}, {10, 8}, {0, 8}, {0, 8}, {0, 0}});
    EXPECT_FALSE(e.output.skipped);
    EXPECT_TRUE(e.output.issues.empty()) << describeAll(g, e.output);
    EXPECT_EQ(e.output.atoms, 4u);
    ASSERT_EQ(e.output.footprint.size(), 4u);
    ASSERT_EQ(e.terminals.size(), 4u);
    float perimeter = 0.0f;
    for (const Terminal& t : e.terminals) perimeter += t.size.x;
    EXPECT_NEAR(perimeter, 36.0f, 1e-4f);
}

double signedArea(const std::vector<glm::vec2>& p) {
    double twice = 0.0;
    for (size_t i = 0; i < p.size(); ++i) {
        const glm::vec2 a = p[i], b = p[(i + 1) % p.size()];
        twice += double(a.x) * b.y - double(b.x) * a.y;
    }
    return 0.5 * twice;
}

TEST(BadFootprintTest, ClockwiseFootprintIsReversedSoFacadesFaceOutwards) {
    const CompiledGrammar g = compileOrFail(kWallGrammar, "walls.grammar");
    const Expansion e = expandOne(g, {{0, 0}, {0, 8}, {10, 8}, {10, 0}});
    EXPECT_FALSE(e.output.skipped);
    EXPECT_TRUE(e.output.issues.empty()) << describeAll(g, e.output);
    EXPECT_NEAR(signedArea(e.output.footprint), 80.0, 1e-6);
    ASSERT_EQ(e.terminals.size(), 4u);
    for (const Terminal& t : e.terminals) {
        // The face's centre minus the footprint's centre points the same way as its normal.
        const glm::vec3 centre = t.position + t.axisX() * (0.5f * t.size.x) + t.axisY() * (0.5f * t.size.y);
        const glm::vec2 outwards = glm::vec2(centre) - glm::vec2(5.0f, 4.0f);
        EXPECT_GT(glm::dot(glm::vec2(t.normal()), outwards), 0.0f);
        EXPECT_NEAR(t.normal().z, 0.0f, 1e-3f);
    }
    // The same facades as the counter-clockwise footprint, in any order.
    const Expansion ccw = expandOne(g, rectangle(10, 8));
    ASSERT_EQ(ccw.terminals.size(), 4u);
    for (const Terminal& t : e.terminals) {
        size_t matches = 0;
        for (const Terminal& u : ccw.terminals) {
            if (glm::distance(t.position, u.position) < 1e-4f &&
                glm::distance(t.normal(), u.normal()) < 1e-3f) {
                ++matches;
            }
        }
        EXPECT_EQ(matches, 1u);
    }
}

TEST(BadFootprintTest, BowTieIsExpandedWithAWarning) {
    const CompiledGrammar g = compileOrFail(kWallGrammar, "walls.grammar");
    // Edges 0 and 2 cross at (4/3, 4/3); the lobes differ, so the net area is not 0.
    const Expansion e = expandOne(g, {{0, 0}, {4, 4}, {4, 0}, {0, 2}});
    EXPECT_FALSE(e.output.skipped);
    EXPECT_EQ(e.output.atoms, 4u);
    EXPECT_EQ(e.terminals.size(), 4u);
    ASSERT_EQ(e.output.issues.size(), 1u) << describeAll(g, e.output);
    EXPECT_EQ(e.output.issues[0].kind, IssueKind::SelfIntersectingFootprint);
    EXPECT_EQ(e.output.issues[0].rule, kNullRule);
    EXPECT_FALSE(issueIsError(IssueKind::SelfIntersectingFootprint));
}

// --- Repeat ----------------------------------------------------------------------------

// Repeat straight on the atoms of a 10 x 4 rectangle: edges of 10, 4, 10 and 4 m.
std::string repeatGrammar(const std::string& size, const std::string& mode, bool margin) {
    return "param zero = 0 in [0, 1];\n"
           "shape tile(triangles = 2);\n"
           "shape margin(triangles = 2);\n"
           "Lot -> Repeat(x, " +
           size + ", " + mode + ") { Tile" + (margin ? ", Margin" : "") +
           " };\n"
           "Tile -> Shape(tile);\n"
           "Margin -> Shape(margin);\n";
}

TEST(BadRepeatTest, InvalidTileSizesDropTheScope) {
    // 0 and negative fold to constants; 0/0 from a parameter is a NaN only at run time.
    for (const char* size : {"0", "-1", "zero / zero", "1 / zero"}) {
        for (const char* mode : {"fit", "equal"}) {
            const CompiledGrammar g = compileOrFail(repeatGrammar(size, mode, true), "repeat.grammar");
            const Expansion e = expandOne(g, rectangle(10, 4));
            EXPECT_TRUE(e.terminals.empty()) << size << " " << mode;
            ASSERT_EQ(e.output.issues.size(), 1u) << size << " " << mode << "\n" << describeAll(g, e.output);
            EXPECT_EQ(e.output.issues[0].kind, IssueKind::InvalidSize);
            EXPECT_EQ(ruleOf(g, e.output.issues[0]), "Lot");
            EXPECT_FALSE(e.output.skipped);
        }
    }
}

TEST(BadRepeatTest, TileLargerThanTheScopeFitsNoTileAndEqualFitsOne) {
    {
        const CompiledGrammar g = compileOrFail(repeatGrammar("20", "fit", true), "repeat.grammar");
        const Expansion e = expandOne(g, rectangle(10, 4));
        EXPECT_TRUE(e.output.issues.empty()) << describeAll(g, e.output);
        // No tile: the whole edge is margin, split into two halves.
        const auto counts = countByShape(g, e.terminals);
        EXPECT_EQ(counts.count("tile"), 0u);
        EXPECT_EQ(counts.at("margin"), 8u);
        float length = 0.0f;
        for (const Terminal& t : e.terminals) length += t.size.x;
        EXPECT_NEAR(length, 28.0f, 1e-4f);
    }
    {
        const CompiledGrammar g = compileOrFail(repeatGrammar("20", "fit", false), "repeat.grammar");
        const Expansion e = expandOne(g, rectangle(10, 4));
        EXPECT_TRUE(e.output.issues.empty()) << describeAll(g, e.output);
        EXPECT_TRUE(e.terminals.empty());
    }
    {
        const CompiledGrammar g = compileOrFail(repeatGrammar("20", "equal", true), "repeat.grammar");
        const Expansion e = expandOne(g, rectangle(10, 4));
        EXPECT_TRUE(e.output.issues.empty()) << describeAll(g, e.output);
        ASSERT_EQ(e.terminals.size(), 4u);
        const float expected[] = {10.0f, 4.0f, 10.0f, 4.0f};
        for (size_t i = 0; i < 4; ++i) {
            EXPECT_EQ(e.terminals[i].shape, g.findShape("tile"));
            EXPECT_NEAR(e.terminals[i].size.x, expected[i], 1e-3f) << i;
        }
    }
}

TEST(BadRepeatTest, TooManyTilesDropTheScopeWithoutWork) {
    const CompiledGrammar g = compileOrFail(repeatGrammar("0.000001", "fit", false), "repeat.grammar");
    Expansion e;
    // Each 10 m edge would take 1e7 tiles of 1 um, above the default 8,388,608 rule applications.
    const double seconds = secondsFor([&] { e = expandOne(g, rectangle(10, 10)); });
    EXPECT_LT(seconds, kNotAHangSeconds);
    EXPECT_TRUE(e.terminals.empty());
    ASSERT_EQ(e.output.issues.size(), 1u) << describeAll(g, e.output);
    EXPECT_EQ(e.output.issues[0].kind, IssueKind::TooManyTiles);
    EXPECT_EQ(ruleOf(g, e.output.issues[0]), "Lot");
}

// --- Split -----------------------------------------------------------------------------

std::string splitGrammar(const std::string& first, const std::string& second) {
    return "param zero = 0 in [0, 1];\n"
           "shape a(triangles = 2);\n"
           "shape b(triangles = 2);\n"
           "shape c(triangles = 2);\n"
           "Lot -> Split(x, " +
           first + ", " + second +
           ", ~1) { A, B, C };\n"
           "A -> Shape(a);\n"
           "B -> Shape(b);\n"
           "C -> Shape(c);\n";
}

TEST(BadSplitTest, NaNAndNegativeSizesCountAsZeroAndAreReportedOnce) {
    for (const char* bad : {"zero / zero", "-3", "-1 / zero"}) {
        const CompiledGrammar g = compileOrFail(splitGrammar(bad, "2"), "split.grammar");
        const Expansion e = expandOne(g, rectangle(10, 4));
        // One report per building and rule, although all four atoms hit it.
        ASSERT_EQ(e.output.issues.size(), 1u) << bad << "\n" << describeAll(g, e.output);
        EXPECT_EQ(e.output.issues[0].kind, IssueKind::InvalidSize);
        EXPECT_EQ(ruleOf(g, e.output.issues[0]), "Lot");
        // Part A is 0 and dropped; B keeps 2 m and C takes the rest.
        const auto counts = countByShape(g, e.terminals);
        EXPECT_EQ(counts.count("a"), 0u) << bad;
        EXPECT_EQ(counts.at("b"), 4u) << bad;
        EXPECT_EQ(counts.at("c"), 4u) << bad;
        for (const Terminal& t : e.terminals) {
            if (t.shape == g.findShape("b")) {
                EXPECT_NEAR(t.size.x, 2.0f, 1e-4f);
            }
        }
    }
}

TEST(BadSplitTest, OverflowingAbsoluteSizesAreScaledToFit) {
    const CompiledGrammar g = compileOrFail(splitGrammar("8", "8"), "split.grammar");
    const Expansion e = expandOne(g, rectangle(10, 4));
    EXPECT_TRUE(e.output.issues.empty()) << describeAll(g, e.output);
    // 8 + 8 on a 10 m edge become 5 + 5 (2 + 2 on a 4 m edge); the ~ part gets nothing.
    const auto counts = countByShape(g, e.terminals);
    EXPECT_EQ(counts.at("a"), 4u);
    EXPECT_EQ(counts.at("b"), 4u);
    EXPECT_EQ(counts.count("c"), 0u);
    const float expected[] = {5.0f, 5.0f, 2.0f, 2.0f, 5.0f, 5.0f, 2.0f, 2.0f};
    ASSERT_EQ(e.terminals.size(), 8u);
    for (size_t i = 0; i < 8; ++i) EXPECT_NEAR(e.terminals[i].size.x, expected[i], 1e-4f) << i;
}

// --- Other invalid run-time values -------------------------------------------------------

struct BadRuntimeValue {
    const char* name;
    const char* grammar; // its rule 'Bad' hits the issue
    IssueKind kind;
    size_t terminals; // what survives on the 10 x 4 rectangle
};

TEST(BadRuntimeValueTest, InvalidAmountsDropTheScopeAndNameTheRule) {
    const std::string prelude = "param zero = 0 in [0, 1];\nshape s(triangles = 2);\n";
    const BadRuntimeValue cases[] = {
        {"Extrude NaN height", "Lot -> Extrude(1) { Bad, NULL };\nBad -> Extrude(zero / zero) { S, S };\n",
         IssueKind::InvalidSize, 0},
        {"Extrude negative scale", "Bad -> Extrude(3, zero - 1) { S, S };\n", IssueKind::InvalidSize, 0},
        {"Extrude on a volume",
         "Lot -> Extrude(1) { F, NULL };\nF -> Extrude(1) { Bad, NULL };\n"
         "Bad -> Extrude(1) { S, S };\n",
         IssueKind::WrongScopeKind, 0},
        {"Branch NaN count", "Bad -> Branch(zero / zero) { S };\n", IssueKind::InvalidCount, 0},
        {"Branch count above 1024", "Bad -> Branch(2000 + zero) { S };\n", IssueKind::InvalidCount, 0},
        {"Translate infinite", "Bad -> Translate(1 / zero, 0, 0) { S };\n", IssueKind::InvalidTransform, 0},
        {"Rotate NaN", "Bad -> Rotate(center, y, zero / zero) { S };\n", IssueKind::InvalidTransform, 0},
        {"Choose all zero", "Bad -> Choose(zero: S, zero: NULL);\n", IssueKind::InvalidProbability, 0},
        {"Choose NaN", "Bad -> Choose(zero / zero: S, 1: NULL);\n", IssueKind::InvalidProbability, 0},
        {"Explode an atom", "Bad -> Explode() { S, S, S, S, S };\n", IssueKind::WrongScopeKind, 0},
        // A bad depth ratio keeps the terminal with the shape's declared ratio.
        {"Shape negative depth ratio", "Bad -> Shape(s, zero - 1);\n", IssueKind::InvalidSize, 4},
    };
    for (const BadRuntimeValue& c : cases) {
        const std::string source = prelude + c.grammar + "S -> Shape(s);\n";
        const CompiledGrammar g = compileOrFail(source, "runtime.grammar");
        if (g.rules.empty()) continue;
        const Expansion e = expandOne(g, rectangle(10, 4));
        EXPECT_EQ(e.terminals.size(), c.terminals) << c.name;
        ASSERT_EQ(e.output.issues.size(), 1u) << c.name << "\n" << describeAll(g, e.output);
        EXPECT_EQ(e.output.issues[0].kind, c.kind) << c.name;
        EXPECT_EQ(ruleOf(g, e.output.issues[0]), "Bad") << c.name;
        EXPECT_FALSE(issueIsError(c.kind)) << c.name; // the rest of the building stands
    }
}

// --- Caps ---------------------------------------------------------------------------

TEST(ExpansionCapTest, CondGuardedRecursionThatNeverStopsHitsTheDepthCap) {
    const CompiledGrammar g = compileOrFail("A -> Cond(depth < 100000) { B, NULL };\n"
                                            "B -> Translate(0, 0, 0) { A };\n",
                                            "depth.grammar");
    Expansion e;
    EXPECT_LT(secondsFor([&] { e = expandOne(g, rectangle(10, 8)); }), kNotAHangSeconds);
    ASSERT_EQ(e.output.issues.size(), 1u) << describeAll(g, e.output);
    const ExpansionIssue& issue = e.output.issues[0];
    EXPECT_EQ(issue.kind, IssueKind::DepthCap);
    EXPECT_TRUE(issueIsError(issue.kind));
    // A sits at even depths; at depth 256 it would push B to 257, one past the cap.
    EXPECT_EQ(ruleOf(g, issue), "A");
    EXPECT_EQ(issue.detail, "depth 257");
    EXPECT_NE(
        describeIssue(g, issue).find("depth.grammar:1:1: rule 'A': error: building 0: recursion depth cap"),
        std::string::npos)
        << describeIssue(g, issue);
}

TEST(ExpansionCapTest, DepthCapCutsOnlyTheBranchAndKeepsTheTerminalsBeforeIt) {
    const CompiledGrammar g = compileOrFail("shape s(triangles = 2);\n"
                                            "A -> Cond(depth < 100000) { B, NULL };\n"
                                            "B -> Branch(2) { A, S };\n"
                                            "S -> Shape(s);\n",
                                            "depth.grammar");
    ExpansionSettings settings;
    settings.limits.maxDepth = 40;
    const Expansion e = expandOne(g, rectangle(10, 8), {}, 0, settings);
    ASSERT_EQ(e.output.issues.size(), 1u) << describeAll(g, e.output);
    EXPECT_EQ(e.output.issues[0].kind, IssueKind::DepthCap);
    EXPECT_EQ(ruleOf(g, e.output.issues[0]), "A");
    // B runs at depths 1, 3, ..., 39 and puts S one deeper: 20 terminals per atom.
    EXPECT_EQ(e.terminals.size(), 4u * 20u);
}

TEST(ExpansionCapTest, BranchExplosionHitsTheOperationCapQuickly) {
    // 2^12 leaves per atom: about 16,400 rule applications, well above the cap of 10,000.
    const CompiledGrammar g = compileOrFail("shape s(triangles = 2);\n"
                                            "A -> Branch(2) { B };\n"
                                            "B -> Cond(level < 12) { A, S };\n"
                                            "S -> Shape(s);\n",
                                            "branch.grammar");
    ExpansionSettings settings;
    settings.limits.maxOperationsPerAtom = 10000;
    Expansion e;
    EXPECT_LT(secondsFor([&] { e = expandOne(g, rectangle(10, 8), {}, 3, settings); }), kNotAHangSeconds);
    // Every atom runs into the cap, so every atom is dropped whole; reported once.
    EXPECT_TRUE(e.terminals.empty());
    EXPECT_EQ(e.output.atoms, 4u);
    const auto capped = issuesOf(e.output, IssueKind::AtomOperationCap);
    ASSERT_EQ(capped.size(), 1u) << describeAll(g, e.output);
    EXPECT_EQ(capped[0]->building, 3u);
    // The issue names the rule whose application crossed the cap: with depth-first order
    // that is the leaf S, applied right after the 10,000th rule application.
    EXPECT_EQ(ruleOf(g, *capped[0]), "S");
    EXPECT_EQ(capped[0]->detail, "more than 10000 rule applications on atom 0");
    EXPECT_EQ(e.output.issues.size(), 1u) << describeAll(g, e.output);

    // The same grammar under the default cap completes: 4096 leaves per atom.
    const Expansion full = expandOne(g, rectangle(10, 8));
    EXPECT_TRUE(full.output.issues.empty()) << describeAll(g, full.output);
    EXPECT_EQ(full.terminals.size(), 4u * 4096u);
}

TEST(ExpansionCapTest, AtomTerminalCapDropsOnlyThatAtomsTerminals) {
    // On a 100 x 1 rectangle the long edges make 200 tiles each, the short ones 2.
    const CompiledGrammar g = compileOrFail("shape tile(triangles = 2);\n"
                                            "Lot -> Repeat(x, 0.5, fit) { Tile };\n"
                                            "Tile -> Shape(tile);\n",
                                            "tiles.grammar");
    ExpansionSettings settings;
    settings.limits.maxTerminalsPerAtom = 100;
    Expansion e;
    EXPECT_LT(secondsFor([&] { e = expandOne(g, rectangle(100, 1), {}, 0, settings); }), kNotAHangSeconds);
    ASSERT_EQ(e.output.issues.size(), 1u) << describeAll(g, e.output);
    EXPECT_EQ(e.output.issues[0].kind, IssueKind::AtomTerminalCap);
    EXPECT_EQ(ruleOf(g, e.output.issues[0]), "Tile");
    EXPECT_EQ(e.output.issues[0].detail, "more than 100 terminals on atom 0");
    // Only the two short edges (x = 100 and x = 0) keep their tiles.
    ASSERT_EQ(e.terminals.size(), 4u);
    for (const Terminal& t : e.terminals) {
        EXPECT_TRUE(std::fabs(t.position.x - 100.0f) < 1e-3f || std::fabs(t.position.x) < 1e-3f)
            << t.position.x;
        EXPECT_NEAR(t.size.x, 0.5f, 1e-4f);
    }
}

TEST(ExpansionCapTest, BatchTerminalCapFailsTheWholeBatch) {
    const CompiledGrammar g = compileOrFail(kWallGrammar, "walls.grammar");
    std::vector<BuildingInput> buildings(3);
    for (uint32_t i = 0; i < 3; ++i) {
        buildings[i].id = 10 + i;
        buildings[i].footprint = rectangle(10, 8, {20.0 * i, 0.0});
    }
    BatchInput input;
    input.grammar = &g;
    input.buildings = buildings;
    input.settings.seed = 1;

    // 3 buildings x 4 walls = 12 terminals: exactly at the cap is fine...
    input.settings.limits.maxTerminalsPerBatch = 12;
    const BatchResult fits = expandBatch(input);
    EXPECT_FALSE(fits.failed);
    EXPECT_EQ(fits.terminals.records.size(), 12u);
    EXPECT_TRUE(fits.issues.empty());

    // ...one below it and nothing is generated.
    input.settings.limits.maxTerminalsPerBatch = 11;
    BatchResult capped;
    EXPECT_LT(secondsFor([&] { capped = expandBatch(input); }), kNotAHangSeconds);
    EXPECT_TRUE(capped.failed);
    EXPECT_TRUE(capped.terminals.records.empty());
    EXPECT_TRUE(capped.extruded.buildings.empty());
    ASSERT_EQ(capped.issues.size(), 1u);
    EXPECT_EQ(capped.issues[0].first.kind, IssueKind::BatchTerminalCap);
    EXPECT_EQ(capped.issues[0].first.rule, kNullRule);
    EXPECT_EQ(capped.issues[0].first.detail, "12 terminals, cap 11");
    EXPECT_TRUE(issueIsError(IssueKind::BatchTerminalCap));
}

} // namespace
} // namespace hexlod::grammar
