// The grammars and species shipped in configs/ are what the demo city is built from, so
// they are held to the numbers configs/grammars/README.md states and to the behaviour the
// grammars promise (ground floors with doors, 200-storey towers, seven distinct trees).
#include "test_support.h"

#include "hexlod/scene/demo_footprints.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>

namespace hexlod::grammar {
namespace {

using test::countByShape;
using test::expandOne;
using test::rectangle;

std::string configPath(const std::string& relative) {
    return std::string(HEXLOD_CONFIGS_DIR) + "/" + relative;
}

// Compiles a shipped grammar; a shipped grammar must not even warn.
CompiledGrammar loadGrammar(const std::string& relative) {
    DiagnosticList diagnostics;
    CompiledGrammar g = compileGrammarFile(configPath(relative), diagnostics);
    EXPECT_TRUE(diagnostics.all().empty()) << relative << ":\n" << diagnostics.formatAll();
    EXPECT_FALSE(g.rules.empty()) << relative;
    return g;
}

bool callsRand(const CompiledGrammar& g, const CompiledRule& rule) {
    for (uint32_t a = 0; a < rule.argumentCount; ++a) {
        const Expression& e = g.expressions[g.arguments[rule.firstArgument + a].expression];
        for (uint32_t i = 0; i < e.count; ++i) {
            if (g.code[e.first + i].op == Opcode::Random) return true;
        }
    }
    return false;
}

size_t stochasticRules(const CompiledGrammar& g) {
    return std::count_if(g.rules.begin(), g.rules.end(),
                         [&](const CompiledRule& r) { return r.op == RuleOp::Choose || callsRand(g, r); });
}

size_t rulesOf(const CompiledGrammar& g, RuleOp op) {
    return std::count_if(g.rules.begin(), g.rules.end(), [&](const CompiledRule& r) { return r.op == op; });
}

// Shapes named by a Shape rule that the axiom can reach, ignoring conditions.
std::set<std::string> reachableShapes(const CompiledGrammar& g) {
    std::vector<bool> seen(g.rules.size(), false);
    std::vector<uint32_t> stack{g.axiom};
    seen[g.axiom] = true;
    std::set<std::string> shapes;
    while (!stack.empty()) {
        const CompiledRule& rule = g.rules[stack.back()];
        stack.pop_back();
        if (rule.op == RuleOp::Shape) shapes.insert(g.shapes[rule.shape].name);
        for (uint32_t s = 0; s < rule.successorCount; ++s) {
            const uint32_t next = g.successors[rule.firstSuccessor + s];
            if (next != kNullRule && !seen[next]) {
                seen[next] = true;
                stack.push_back(next);
            }
        }
    }
    return shapes;
}

std::set<std::string> declaredShapes(const CompiledGrammar& g) {
    std::set<std::string> names;
    for (const ShapeInfo& s : g.shapes) names.insert(s.name);
    return names;
}

// Expands demo footprints with the per-building `floors` the demo city uses.
std::map<std::string, size_t> expandDemo(const CompiledGrammar& g, uint32_t count,
                                         std::vector<size_t>* perBuilding) {
    const std::vector<BuildingInput> buildings = scene::makeDemoFootprints({count, 1, 60.0});
    std::map<std::string, size_t> total;
    for (const BuildingInput& building : buildings) {
        const test::Expansion e =
            expandOne(g, building.footprint, scene::demoParameterOverrides(g, 1, building.id), building.id);
        EXPECT_TRUE(e.output.issues.empty())
            << g.name << " building " << building.id << ": " << describeIssue(g, e.output.issues.front());
        for (const auto& [name, n] : countByShape(g, e.terminals)) total[name] += n;
        if (perBuilding) perBuilding->push_back(e.terminals.size());
    }
    return total;
}

std::set<std::string> keys(const std::map<std::string, size_t>& counts) {
    std::set<std::string> names;
    for (const auto& [name, n] : counts) names.insert(name);
    return names;
}

// Elevations rounded to centimetres, so float noise does not split one storey into two.
std::set<long> elevationsOf(const CompiledGrammar& g, const std::vector<Terminal>& terminals,
                            const std::set<std::string>& shapes) {
    std::set<long> elevations;
    for (const Terminal& t : terminals) {
        if (shapes.count(g.shapes[t.shape].name)) elevations.insert(std::lround(t.position.z * 100.0f));
    }
    return elevations;
}

TEST(ShippedGrammars, DeclaredShapesHaveSaneBounds) {
    for (const char* file :
         {"grammars/residential.grammar", "grammars/business.grammar", "grammars/tree.grammar"}) {
        const CompiledGrammar g = loadGrammar(file);
        for (const ShapeInfo& s : g.shapes) {
            // A shape of depth 0 is a flat tile, one quad (tests/render/procedural_meshes_test.cpp).
            EXPECT_GE(s.triangles, s.depthRatio == 0.0f ? 2u : 50u) << file << " " << s.name;
            EXPECT_LE(s.triangles, 500u) << file << " " << s.name;
            EXPECT_GT(s.width, 0.0f) << file << " " << s.name;
            EXPECT_GT(s.height, 0.0f) << file << " " << s.name;
            EXPECT_LE(s.depthRatio, 5.0f) << file << " " << s.name;
        }
        EXPECT_EQ(reachableShapes(g), declaredShapes(g)) << file << ": a declared shape no rule emits";
    }
}

// The counts below are the ones configs/grammars/README.md states; update both together.
TEST(ResidentialGrammar, CountsMatchTheReadme) {
    const CompiledGrammar g = loadGrammar("grammars/residential.grammar");
    EXPECT_EQ(g.rules.size(), 54u);
    EXPECT_EQ(stochasticRules(g), 9u);
    EXPECT_EQ(rulesOf(g, RuleOp::Choose), 7u);
    EXPECT_EQ(rulesOf(g, RuleOp::Cond), 5u);
    EXPECT_EQ(g.shapes.size(), 19u);
    EXPECT_GE(g.findParameter("floors"), 0);
    for (RuleOp op : {RuleOp::Extrude, RuleOp::Split, RuleOp::Repeat, RuleOp::Rotate}) {
        EXPECT_GT(rulesOf(g, op), 0u) << ruleOpName(op);
    }
}

TEST(ResidentialGrammar, DemoCityUsesEveryShapeAtAPlausibleSize) {
    const CompiledGrammar g = loadGrammar("grammars/residential.grammar");
    std::vector<size_t> perBuilding;
    const std::map<std::string, size_t> counts = expandDemo(g, 64, &perBuilding);
    EXPECT_EQ(keys(counts), declaredShapes(g));
    for (size_t i = 0; i < perBuilding.size(); ++i) {
        EXPECT_GE(perBuilding[i], 100u) << "building " << i;
        EXPECT_LE(perBuilding[i], 3000u) << "building " << i;
    }
}

TEST(ResidentialGrammar, DoorsAndShopsStayOnTheGroundFloorAndRoofsOnTop) {
    const CompiledGrammar g = loadGrammar("grammars/residential.grammar");
    const float floorH = g.params[g.findParameter("floor_h")].defaultValue;
    const float floors = g.params[g.findParameter("floors")].defaultValue;
    const float eaves = floors * floorH + g.params[g.findParameter("cornice_h")].defaultValue;
    // Building 1 has a pitched roof (every fourth building, id % 4 == 3, is flat).
    const test::Expansion e = expandOne(g, rectangle(30, 14), {}, 1);
    ASSERT_TRUE(e.output.issues.empty());
    EXPECT_NEAR(e.output.height, eaves, 1e-3);
    std::map<std::string, size_t> counts = countByShape(g, e.terminals);
    EXPECT_GT(counts["door"], 0u);
    EXPECT_GT(counts["roof_tile"], 0u);
    EXPECT_EQ(counts["parapet"], 0u);
    for (const Terminal& t : e.terminals) {
        const std::string& name = g.shapes[t.shape].name;
        if (name == "door" || name == "stairs" || name == "shop_window" || name == "awning") {
            EXPECT_LT(t.position.z, floorH) << name << " above the ground floor";
        }
        if (name == "balcony" || name == "ledge") {
            EXPECT_GE(t.position.z, floorH - 1e-3f) << name;
        }
        if (name == "roof_tile") {
            EXPECT_GE(t.position.z, eaves - 1e-3f);
            EXPECT_GT(t.normal().z, 0.3f) << "roof slopes face the sky";
        }
    }
    const test::Expansion flat = expandOne(g, rectangle(30, 14), {}, 3);
    std::map<std::string, size_t> flatCounts = countByShape(g, flat.terminals);
    EXPECT_EQ(flatCounts["roof_tile"], 0u);
    EXPECT_EQ(flatCounts["parapet"], 4u) << "one parapet per edge";
}

TEST(ResidentialGrammar, OneBuildingExpandsToTheSameBytesTwice) {
    const CompiledGrammar g = loadGrammar("grammars/residential.grammar");
    const std::vector<glm::dvec2> footprint = {{0, 0}, {24, 0}, {24, 9}, {11, 9}, {11, 20}, {0, 20}};
    const test::Expansion a = expandOne(g, footprint, {{"floors", 6}}, 7);
    const test::Expansion b = expandOne(g, footprint, {{"floors", 6}}, 7);
    ASSERT_GT(a.output.terminals.size(), 100u);
    ASSERT_EQ(a.output.terminals.size(), b.output.terminals.size());
    EXPECT_EQ(std::memcmp(a.output.terminals.data(), b.output.terminals.data(),
                          a.output.terminals.size() * sizeof(TerminalRecord)),
              0);
    // The stochastic rules really are keyed by building: another id gives another facade.
    const test::Expansion other = expandOne(g, footprint, {{"floors", 6}}, 8);
    EXPECT_NE(countByShape(g, a.terminals), countByShape(g, other.terminals));
}

TEST(BusinessGrammar, CountsMatchTheReadme) {
    const CompiledGrammar g = loadGrammar("grammars/business.grammar");
    EXPECT_EQ(g.rules.size(), 33u);
    EXPECT_EQ(stochasticRules(g), 0u);
    EXPECT_EQ(rulesOf(g, RuleOp::Cond), 6u);
    EXPECT_EQ(g.shapes.size(), 11u);
    const int floors = g.findParameter("floors");
    ASSERT_GE(floors, 0);
    EXPECT_GE(g.params[floors].maxValue, 250.0f);
}

TEST(BusinessGrammar, DemoCityUsesEveryShape) {
    const CompiledGrammar g = loadGrammar("grammars/business.grammar");
    std::vector<size_t> perBuilding;
    EXPECT_EQ(keys(expandDemo(g, 64, &perBuilding)), declaredShapes(g));
    for (size_t n : perBuilding) EXPECT_GE(n, 300u);
}

TEST(BusinessGrammar, TwoHundredStoreysGiveTwoHundredFloorLevels) {
    const CompiledGrammar g = loadGrammar("grammars/business.grammar");
    const std::vector<glm::dvec2> lot = rectangle(40, 30);
    const test::Expansion tall = expandOne(g, lot, {{"floors", 200}});
    const test::Expansion low = expandOne(g, lot, {{"floors", 40}});
    ASSERT_TRUE(tall.output.issues.empty()) << describeIssue(g, tall.output.issues.front());
    EXPECT_EQ(elevationsOf(g, tall.terminals, {"curtain_glass", "louver"}).size(), 200u);
    EXPECT_EQ(elevationsOf(g, low.terminals, {"curtain_glass", "louver"}).size(), 40u);
    // A plant floor every 15 storeys (the 15th, 30th, ... above the lobby).
    EXPECT_EQ(elevationsOf(g, tall.terminals, {"louver"}).size(), 13u);
    // Setbacks after storeys 50, 100 and 150, each a terrace on every edge.
    EXPECT_EQ(elevationsOf(g, tall.terminals, {"terrace_deck"}).size(), 3u);
    EXPECT_EQ(countByShape(g, tall.terminals)["terrace_deck"], 12u);
    EXPECT_EQ(countByShape(g, tall.terminals)["spire"], 1u);
    const size_t tallGlass = countByShape(g, tall.terminals)["curtain_glass"];
    const size_t lowGlass = countByShape(g, low.terminals)["curtain_glass"];
    EXPECT_GT(tallGlass, 4 * lowGlass) << "setbacks narrow the tower, but not by a fifth";
    // Lobby 7 m + 200 x 3.8 m + crown 8 m.
    EXPECT_NEAR(tall.output.height, 7.0f + 200 * 3.8f + 8.0f, 0.05f);
}

TEST(TreeGrammar, CountsMatchTheReadme) {
    const CompiledGrammar g = loadGrammar("grammars/tree.grammar");
    EXPECT_EQ(g.rules.size(), 23u);
    EXPECT_EQ(stochasticRules(g), 7u);
    EXPECT_EQ(rulesOf(g, RuleOp::Cond), 5u);
    EXPECT_EQ(rulesOf(g, RuleOp::Branch), 2u);
    EXPECT_EQ(g.shapes.size(), 4u);
    for (const char* name :
         {"trunk_h", "branch_angle", "taper", "twist", "max_level", "leaf_size", "leaf_density"}) {
        EXPECT_GE(g.findParameter(name), 0) << name;
    }
}

TEST(TreeGrammar, OneTreePerFootprintWhateverItsSize) {
    const CompiledGrammar g = loadGrammar("grammars/tree.grammar");
    const test::Expansion small = expandOne(g, rectangle(0.4, 0.4));
    const test::Expansion large = expandOne(g, rectangle(12, 9));
    ASSERT_TRUE(small.output.issues.empty());
    EXPECT_EQ(small.output.atoms, 4u);
    EXPECT_GE(small.terminals.size(), 200u);
    EXPECT_LE(small.terminals.size(), 5000u);
    EXPECT_GT(countByShape(g, small.terminals)["leaf"], 0u);
    // The trunk is shrunk to trunk_w, so a large footprint grows the same tree.
    EXPECT_EQ(small.terminals.size(), large.terminals.size());
    const float trunkH = g.params[g.findParameter("trunk_h")].defaultValue;
    EXPECT_NEAR(small.output.height, trunkH, 1e-3) << "the extruded set is the trunk";
}

struct Species {
    std::string name;
    std::vector<ParameterOverride> params;
};

std::vector<Species> readSpecies() {
    std::ifstream in(configPath("species.json"));
    EXPECT_TRUE(in.good()) << configPath("species.json");
    const nlohmann::json doc = nlohmann::json::parse(in);
    std::vector<Species> species;
    for (const nlohmann::json& entry : doc.at("species")) {
        EXPECT_EQ(entry.at("grammar").get<std::string>(), "grammars/tree.grammar");
        Species s{entry.at("name").get<std::string>(), {}};
        for (const auto& [name, value] : entry.at("params").items())
            s.params.push_back({name, value.get<double>()});
        species.push_back(std::move(s));
    }
    return species;
}

TEST(TreeSpecies, SevenSpeciesGrowSevenDifferentTrees) {
    const CompiledGrammar g = loadGrammar("grammars/tree.grammar");
    const std::vector<Species> species = readSpecies();
    ASSERT_EQ(species.size(), 7u);
    std::set<std::string> names, shapesUsed;
    std::vector<size_t> counts;
    std::vector<glm::vec3> extents;
    for (const Species& s : species) {
        names.insert(s.name);
        DiagnosticList diagnostics;
        resolveParameters(g, s.params, diagnostics);
        EXPECT_TRUE(diagnostics.all().empty()) << s.name << ":\n" << diagnostics.formatAll();

        const test::Expansion e = expandOne(g, rectangle(0.4, 0.4), s.params);
        EXPECT_TRUE(e.output.issues.empty()) << s.name;
        const std::map<std::string, size_t> byShape = countByShape(g, e.terminals);
        EXPECT_GT(byShape.count("leaf") ? byShape.at("leaf") : 0, 0u) << s.name << " has no leaves";
        EXPECT_GT(byShape.count("bark") ? byShape.at("bark") : 0, 0u) << s.name << " has no trunk";
        for (const auto& [name, n] : byShape) shapesUsed.insert(name);
        glm::vec3 lo(1e9f), hi(-1e9f);
        for (const Terminal& t : e.terminals) lo = glm::min(lo, t.position), hi = glm::max(hi, t.position);
        counts.push_back(e.terminals.size());
        extents.push_back(hi - lo);
        EXPECT_GT(hi.z, 1.0f) << s.name << " is no taller than a shrub";
        EXPECT_LT(hi.z, 40.0f) << s.name;
    }
    EXPECT_EQ(names.size(), 7u) << "species names must be unique";
    EXPECT_EQ(shapesUsed, declaredShapes(g)) << "every tree shape is used by some species";
    for (size_t a = 0; a < species.size(); ++a) {
        for (size_t b = a + 1; b < species.size(); ++b) {
            EXPECT_NE(counts[a], counts[b]) << species[a].name << " and " << species[b].name;
            EXPECT_GT(glm::length(extents[a] - extents[b]), 0.1f)
                << species[a].name << " and " << species[b].name;
        }
    }
}

} // namespace
} // namespace hexlod::grammar
