#include "hexlod/grammar/parser.h"

#include <gtest/gtest.h>

namespace hexlod::grammar {
namespace {

TEST(Parser, DeclarationsAndRules) {
    DiagnosticList d;
    const GrammarAst ast = parseGrammar("param h = -2 in [-5, 1e3];\n"
                                        "shape w(width = 1.5, triangles = 40);\n"
                                        "extruded_set F, G;\n"
                                        "A -> Split(y, 2, ~1) { F, NULL };\n"
                                        "F -> Choose(0.3: G, 0.7: H);\n",
                                        "p.grammar", d);
    ASSERT_FALSE(d.hasErrors()) << d.formatAll();
    ASSERT_EQ(ast.params.size(), 1u);
    EXPECT_EQ(ast.params[0].defaultValue, -2.0);
    EXPECT_EQ(ast.params[0].maxValue, 1000.0);
    ASSERT_EQ(ast.shapes.size(), 1u);
    EXPECT_EQ(ast.shapes[0].fields.size(), 2u);
    EXPECT_EQ(ast.extrudedStops.size(), 2u);
    ASSERT_EQ(ast.rules.size(), 2u);
    const RuleDecl& split = ast.rules[0];
    EXPECT_EQ(split.operation, "Split");
    ASSERT_EQ(split.arguments.size(), 3u);
    EXPECT_FALSE(split.arguments[1].relative);
    EXPECT_TRUE(split.arguments[2].relative);
    ASSERT_EQ(split.successors.size(), 2u);
    EXPECT_EQ(split.successors[1].name, "NULL");
    EXPECT_EQ(split.location.line, 4u);
    const RuleDecl& choose = ast.rules[1];
    EXPECT_EQ(choose.arguments[1].label, "H");
    EXPECT_FALSE(choose.hasSuccessorBlock);
}

TEST(Parser, ExpressionPrecedence) {
    DiagnosticList d;
    const GrammarAst ast =
        parseGrammar("A -> Extrude(1 + 2 * 3 < 4 || !b && c ? x : y) { B, C };", "p.grammar", d);
    ASSERT_FALSE(d.hasErrors()) << d.formatAll();
    const ExprNode& root = *ast.rules[0].arguments[0].value;
    ASSERT_EQ(root.kind, ExprNode::Kind::Ternary);
    const ExprNode& orNode = *root.children[0];
    ASSERT_EQ(orNode.op, TokenKind::OrOr);
    EXPECT_EQ(orNode.children[0]->op, TokenKind::Less);
    EXPECT_EQ(orNode.children[1]->op, TokenKind::AndAnd);
    const ExprNode& sum = *orNode.children[0]->children[0];
    EXPECT_EQ(sum.op, TokenKind::Plus);
    EXPECT_EQ(sum.children[1]->op, TokenKind::Star);
}

TEST(Parser, RecoversAtSemicolonsAndReportsEveryError) {
    DiagnosticList d;
    const GrammarAst ast =
        parseGrammar("A -> Split(x 1) { B };\nB -> Shape(w);\nC Shape(w);\nD -> NULL;\n", "p.grammar", d);
    ASSERT_EQ(d.all().size(), 2u) << d.formatAll();
    EXPECT_EQ(formatDiagnostic(d.all()[0]),
              "p.grammar:1:14: error: expected ')' to close the argument list of Split, "
              "found '1'");
    EXPECT_EQ(formatDiagnostic(d.all()[1]),
              "p.grammar:3:3: error: expected '->' after the rule name 'C', found 'Shape'");
    EXPECT_EQ(ast.rules.size(), 2u); // B and D survive
}

TEST(Parser, DeepNestingIsAnErrorNotAStackOverflow) {
    DiagnosticList d;
    std::string deep =
        "A -> Extrude(" + std::string(5000, '(') + "1" + std::string(5000, ')') + ") { B, C };";
    parseGrammar(deep, "p.grammar", d);
    ASSERT_TRUE(d.hasErrors());
    EXPECT_NE(d.all()[0].message.find("nested too deeply"), std::string::npos);
}

TEST(Parser, LongOperatorChainsAreBounded) {
    DiagnosticList d;
    std::string chain = "A -> Extrude(1";
    for (int i = 0; i < 10000; ++i) chain += "+1";
    chain += ") { B, C };";
    parseGrammar(chain, "p.grammar", d);
    ASSERT_TRUE(d.hasErrors());
    EXPECT_NE(d.all()[0].message.find("too long"), std::string::npos);
}

} // namespace
} // namespace hexlod::grammar
