// Which rules and shapes a grammar can reach: what a scene loads meshes and bakes impostors for.
#include "hexlod/grammar/rule_reachability.h"
#include "test_support.h"

#include <gtest/gtest.h>

namespace hexlod::grammar {
namespace {

constexpr const char* kGrammar = R"(
shape used_a(triangles = 10);
shape used_b(triangles = 10);
shape only_declared(triangles = 10);
shape behind_dead_rule(triangles = 10);
shape chosen(triangles = 10);
Lot -> Extrude(10) { Face, NULL };
Face -> Split(y, 3, ~1) { A, B };
A -> Cond(height > 100) { EmitA, Pick };
EmitA -> Shape(used_a);
B -> Shape(used_b);
Pick -> Choose(0: Chosen, 1: NULL);
Chosen -> Shape(chosen);
Dead -> Shape(behind_dead_rule);
)";

TEST(RuleReachabilityTest, ShapesBehindReachableRulesCountWhateverTheirConditions) {
    CompiledGrammar g = test::compileOrFail(kGrammar);
    ASSERT_FALSE(g.rules.empty());
    std::vector<bool> emitted = emittedShapes(g);
    ASSERT_EQ(emitted.size(), 5u);
    EXPECT_TRUE(emitted[g.findShape("used_a")]);
    EXPECT_TRUE(emitted[g.findShape("used_b")]);
    // A Choose branch of probability 0 is still a branch: the analysis is conservative.
    EXPECT_TRUE(emitted[g.findShape("chosen")]);
    EXPECT_FALSE(emitted[g.findShape("only_declared")]);
    EXPECT_FALSE(emitted[g.findShape("behind_dead_rule")]);
    std::vector<bool> reached = reachableRules(g);
    EXPECT_FALSE(reached[g.findRule("Dead")]);
    EXPECT_TRUE(reached[g.findRule("Pick")]);
}

TEST(RuleReachabilityTest, AnEmptyGrammarReachesNothing) {
    CompiledGrammar empty;
    EXPECT_TRUE(reachableRules(empty).empty());
    EXPECT_TRUE(emittedShapes(empty).empty());
}

} // namespace
} // namespace hexlod::grammar
