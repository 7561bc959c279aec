// Expressions: constant folding, operator semantics, functions and type checking.
#include "hexlod/grammar/compiled_grammar.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hexlod::grammar {
namespace {

// Compiles `A -> Extrude(expr) { NULL, NULL };` and returns the folded constant.
float fold(const std::string& expression) {
    DiagnosticList d;
    const CompiledGrammar g =
        compileGrammar("A -> Extrude(" + expression + ") { NULL, NULL };", "e.grammar", d);
    EXPECT_FALSE(d.hasErrors()) << d.formatAll();
    if (g.expressions.empty()) return NAN;
    EXPECT_TRUE(g.expressions[0].isConstant);
    return g.expressions[0].constantValue;
}

TEST(Expressions, ArithmeticAndPrecedence) {
    EXPECT_FLOAT_EQ(fold("1 + 2 * 3"), 7);
    EXPECT_FLOAT_EQ(fold("(1 + 2) * 3"), 9);
    EXPECT_FLOAT_EQ(fold("10 - 4 - 3"), 3); // left associative
    EXPECT_FLOAT_EQ(fold("2 * -3"), -6);
    EXPECT_FLOAT_EQ(fold("7 % 4"), 3);
    EXPECT_FLOAT_EQ(fold("1 / 4"), 0.25f);
}

TEST(Expressions, ComparisonLogicAndTernary) {
    EXPECT_FLOAT_EQ(fold("1 < 2 ? 5 : 6"), 5);
    EXPECT_FLOAT_EQ(fold("1 >= 2 || 3 == 3 ? 5 : 6"), 5);
    EXPECT_FLOAT_EQ(fold("!(1 < 2) && true ? 5 : 6"), 6);
    EXPECT_FLOAT_EQ(fold("(1 < 2) == (3 < 4) ? 1 : 0"), 1);
}

TEST(Expressions, Functions) {
    EXPECT_FLOAT_EQ(fold("min(3, 4) + max(3, 4)"), 7);
    EXPECT_FLOAT_EQ(fold("abs(-2) + floor(1.7) + ceil(1.2) + round(2.5)"), 2 + 1 + 2 + 2);
    EXPECT_FLOAT_EQ(fold("sqrt(16)"), 4);
    EXPECT_NEAR(fold("sin(30) + cos(60)"), 1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(fold("pow(2, 10)"), 1024);
    EXPECT_FLOAT_EQ(fold("clamp(5, 0, 2) + clamp(-1, 0, 2)"), 2);
    EXPECT_NEAR(fold("pi"), 3.14159265f, 1e-6f);
}

TEST(Expressions, ParametersAndAccessorsAreNotFolded) {
    DiagnosticList d;
    const CompiledGrammar g = compileGrammar(
        "param p = 2 in [0, 5];\nA -> Extrude(p * width + rand(0, 1)) { NULL, NULL };", "e.grammar", d);
    ASSERT_FALSE(d.hasErrors()) << d.formatAll();
    ASSERT_EQ(g.expressions.size(), 1u);
    EXPECT_FALSE(g.expressions[0].isConstant);
    EXPECT_EQ(g.code[g.expressions[0].first].op, Opcode::LoadParam);
}

TEST(Expressions, TypeErrorsNameWhatWasExpected) {
    DiagnosticList d;
    compileGrammar("A -> Extrude(1 + (2 < 3)) { NULL, NULL };", "e.grammar", d);
    ASSERT_TRUE(d.hasErrors());
    EXPECT_EQ(formatDiagnostic(d.all()[0]),
              "e.grammar:1:21: error: type error: operator '+' needs a number, found a boolean");
}

TEST(Expressions, TooDeepForTheEvaluationStack) {
    // A ternary keeps its condition and first branch on the stack while the second branch
    // runs, so 20 ternaries nested in second branches need 40 slots; 32 exist.
    std::string expression;
    for (int i = 0; i < 20; ++i) expression += "true ? 1 : ";
    expression += "1";
    DiagnosticList d;
    compileGrammar("A -> Extrude(" + expression + ") { NULL, NULL };", "e.grammar", d);
    ASSERT_TRUE(d.hasErrors());
    EXPECT_NE(d.formatAll().find("too complex"), std::string::npos);
}

TEST(Expressions, ContentHashFollowsTheCompiledForm) {
    DiagnosticList d;
    const auto hash = [&](const std::string& source) {
        return compileGrammar(source, "e.grammar", d).contentHash;
    };
    const uint64_t base = hash("A -> Extrude(3) { NULL, NULL };");
    EXPECT_EQ(base, hash("A   ->   Extrude( 3 ) { NULL , NULL } ; # same grammar"));
    EXPECT_NE(base, hash("A -> Extrude(4) { NULL, NULL };"));
    EXPECT_NE(base, hash("A -> Extrude(3, 2) { NULL, NULL };"));
}

} // namespace
} // namespace hexlod::grammar
