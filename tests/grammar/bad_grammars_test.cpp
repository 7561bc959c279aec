// Robustness of the grammar front end: every bad grammar below must be rejected with one
// diagnostic at the place a user would look ("bad.grammar:line:col") and a message that
// says what is wrong. The table pins the exact location so that a regression in token
// positions or error recovery shows up as a failing case, not as a vaguer message.
#include "test_support.h"

#include "hexlod/grammar/compiled_grammar.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

namespace hexlod::grammar {
namespace {

struct BadGrammar {
    std::string name;     // test name suffix
    std::string source;   // the grammar text
    std::string location; // expected "file:line:col" of the first error
    std::string message;  // expected substring of that error's message
    size_t errors = 1;    // expected number of errors (one mistake, one diagnostic)
};

std::ostream& operator<<(std::ostream& out, const BadGrammar& c) {
    return out << c.name;
}

// `count` copies of `text`.
std::string repeated(const std::string& text, size_t count) {
    std::string out;
    for (size_t i = 0; i < count; ++i) out += text;
    return out;
}

// The cases are grouped as in docs/grammar.md: syntax, rules and their arity, names,
// recursion, types, declarations, then limits. Columns are 1-based.
std::vector<BadGrammar> badGrammars() {
    std::vector<BadGrammar> cases = {
        // --- Syntax -------------------------------------------------------------------
        // The missing ';' belongs to line 1: pointing at the next rule's name on line 2
        // sends the user to a line that is fine. Expected: just after the '}' (1:25).
        {"MissingSemicolon", "A -> Extrude(3) { B, B }\nB -> NULL;\n", "bad.grammar:1:25",
         "expected ';' after the rule 'A'"},
        {"MissingArrow", "A Extrude(3) { B, B };\nB -> NULL;\n", "bad.grammar:1:3",
         "expected '->' after the rule name 'A', found 'Extrude'"},
        {"UnbalancedParenthesis", "A -> Extrude((3) { B, B };\nB -> NULL;\n", "bad.grammar:1:18",
         "expected ')' to close the argument list of Extrude, found '{'"},
        {"UnclosedCall", "A -> Cond(depth < 3 { NULL };\n", "bad.grammar:1:21",
         "expected ')' to close the argument list of Cond"},
        {"ExtraClosingParenthesis", "A -> Extrude(3)) { B, B };\nB -> NULL;\n", "bad.grammar:1:16",
         "found ')'"},
        {"UnbalancedBrace", "A -> Extrude(3) { B, B ;\nB -> NULL;\n", "bad.grammar:1:24",
         "expected '}' to close the successor list, found ';'"},
        {"ParenthesisClosesBraces", "A -> Split(x, 1, 2) { NULL, NULL) };\n", "bad.grammar:1:33",
         "expected '}' to close the successor list, found ')'"},
        {"StrayCharacter", "A -> NULL; $\n", "bad.grammar:1:12", "unexpected character '$'"},
        {"StrayControlByte", "A -> \x01NULL;\n", "bad.grammar:1:6", "unexpected byte"},
        {"MalformedNumber", "A -> Extrude(1.2.3) { B, B };\nB -> NULL;\n", "bad.grammar:1:14",
         "malformed number '1.2.3'"},
        // An exponent without digits is one malformed number, as in C, not the number 1.5
        // followed by a stray name 'e'.
        {"ExponentWithoutDigits", "A -> Extrude(1.5e) { B, B };\nB -> NULL;\n", "bad.grammar:1:14",
         "malformed number '1.5e'"},
        // 1e999 is well formed but does not fit: the message should say so.
        {"NumberOutOfRange", "A -> Extrude(1e999) { B, B };\nB -> NULL;\n", "bad.grammar:1:14",
         "out of range"},
        {"MissingOperand", "A -> Extrude(3 +) { NULL, NULL };\n", "bad.grammar:1:17",
         "expected an expression, found ')'"},
        {"NotADeclaration", "A -> NULL;\n-> NULL;\n", "bad.grammar:2:1",
         "expected a declaration (param, shape, extruded_set or a rule), found '->'"},
        {"ParameterWithoutRange", "param h = 3;\nA -> NULL;\n", "bad.grammar:1:12",
         "expected 'in [min, max]' after the default of parameter 'h'"},

        // --- Operations and arity -----------------------------------------------------
        {"UnknownOperation", "A -> Extrud(3) { B, B };\nB -> NULL;\n", "bad.grammar:1:6",
         "unknown rule operation 'Extrud'"},
        {"SplitSizesVersusSuccessors", "A -> Split(x, 1, 2) { B };\nB -> NULL;\n", "bad.grammar:1:6",
         "wrong number of successors for Split: expected 2 in { }, found 1"},
        {"ExtrudeOneSuccessor", "A -> Extrude(3) { B };\nB -> NULL;\n", "bad.grammar:1:6",
         "wrong number of successors for Extrude: expected 2 in { }, found 1"},
        {"ExtrudeNoArguments", "A -> Extrude() { B, B };\nB -> NULL;\n", "bad.grammar:1:6",
         "wrong number of arguments to Extrude: expected 1 to 3, found 0"},
        {"ExtrudeFourArguments", "A -> Extrude(3, 1, 2, 4) { NULL, NULL };\n", "bad.grammar:1:6",
         "wrong number of arguments to Extrude: expected 1 to 3, found 4"},
        {"TranslateTwoArguments", "A -> Translate(0, 0) { NULL };\n", "bad.grammar:1:6",
         "wrong number of arguments to Translate: expected 3, found 2"},
        {"TranslateTwoSuccessors", "A -> Translate(0, 0, 0) { NULL, NULL };\n", "bad.grammar:1:6",
         "wrong number of successors for Translate: expected 1 in { }, found 2"},
        {"CondThreeSuccessors", "A -> Cond(true) { NULL, NULL, NULL };\n", "bad.grammar:1:6",
         "wrong number of successors for Cond: expected 1 to 2 in { }, found 3"},
        {"ExplodeOneSuccessor", "A -> Explode() { NULL };\n", "bad.grammar:1:6",
         "wrong number of successors for Explode: expected 5 in { }, found 1"},
        // Branch(3) takes {A} or three successors; "expected 1" alone hides the second form.
        {"BranchSuccessorsVersusCount", "A -> Branch(3) { NULL, NULL };\n", "bad.grammar:1:6",
         "expected 1 or 3"},
        {"BranchCountZero", "A -> Branch(0) { NULL };\n", "bad.grammar:1:13",
         "Branch count must be between 1 and 1024"},
        {"ShapeWithSuccessors", "shape w(triangles = 2);\nA -> Shape(w) { NULL };\n", "bad.grammar:2:6",
         "Shape takes no successors"},
        {"ShapeNameIsANumber", "A -> Shape(3);\n", "bad.grammar:1:12",
         "expected a shape name as the first argument of Shape"},
        {"NullWithArguments", "A -> NULL(1);\n", "bad.grammar:1:6",
         "wrong number of arguments to NULL: expected 0, found 1"},
        {"FunctionArity", "A -> Extrude(min(1)) { NULL, NULL };\n", "bad.grammar:1:14",
         "function 'min' takes 2 argument(s), found 1"},
        {"BadAxis", "A -> Split(w, 1) { NULL };\n", "bad.grammar:1:12", "expected an axis (x|y|z) in Split"},
        {"BadRepeatMode", "A -> Repeat(x, 1, fill) { NULL };\n", "bad.grammar:1:19",
         "expected a repeat mode (fit|equal) in Repeat"},
        {"BadPivot", "A -> Rotate(middle, z, 3) { NULL };\n", "bad.grammar:1:13",
         "expected a pivot (origin|center) in Rotate"},
        // The '~' is the offending token, not the number after it.
        {"TildeOutsideSplit", "A -> Extrude(~3) { NULL, NULL };\n", "bad.grammar:1:14",
         "'~' sizes are only allowed in Split"},
        {"LabelOutsideChoose", "A -> Split(x, 1: B) { NULL };\nB -> NULL;\n", "bad.grammar:1:18",
         "':' successors are only allowed in Choose"},
        {"ChooseWithoutLabels", "A -> Choose(1, 2);\n", "bad.grammar:1:13",
         "Choose needs 'probability: Successor' pairs"},
        {"ChooseNegativeProbability", "A -> Choose(-1: NULL, 2: NULL);\n", "bad.grammar:1:13",
         "a probability of Choose must be finite and not negative"},
        {"ProjectSameAxisTwice", "A -> Project(x, x) { NULL };\n", "bad.grammar:1:17",
         "Project needs two different axes"},

        // --- Names --------------------------------------------------------------------
        {"UndefinedSuccessor", "A -> Extrude(3) { B, Windw };\nB -> NULL;\n", "bad.grammar:1:22",
         "undefined successor 'Windw' in rule 'A'"},
        {"UnknownParameter", "param floor_h = 3 in [2, 4];\nA -> Extrude(flor_h) { NULL, NULL };\n",
         "bad.grammar:2:14", "unknown parameter or accessor 'flor_h'"},
        {"UnknownAccessor", "A -> Cond(widht > 2) { NULL };\n", "bad.grammar:1:11",
         "unknown parameter or accessor 'widht'"},
        {"UnknownFunction", "A -> Extrude(sqr(4)) { NULL, NULL };\n", "bad.grammar:1:14",
         "unknown function 'sqr'"},
        {"UnknownShape", "shape window(triangles = 2);\nA -> Shape(windw);\n", "bad.grammar:2:12",
         "unknown shape 'windw'"},
        {"RuleUsedAsValue", "A -> Extrude(A) { NULL, NULL };\n", "bad.grammar:1:14",
         "'A' names a rule or shape, not a value"},
        {"ExtrudedSetUnknownRule", "extruded_set B;\nA -> NULL;\n", "bad.grammar:1:14",
         "extruded_set names unknown rule 'B'"},
        {"RuleNamedNull", "NULL -> NULL;\n", "bad.grammar:1:1", "'NULL' is reserved and cannot name a rule"},

        // --- Unbounded recursion --------------------------------------------------------
        {"SelfRecursion", "A -> Translate(0, 0, 1) { A };\n", "bad.grammar:1:1",
         "unbounded recursion: rule 'A' can never end (A -> A)"},
        {"BranchCycle", "A -> Branch(2) { A };\n", "bad.grammar:1:1",
         "unbounded recursion: rule 'A' can never end (A -> A)"},
        {"TwoRuleCycle", "A -> Translate(0, 0, 1) { B };\nB -> Rotate(origin, z, 90) { A };\n",
         "bad.grammar:1:1", "unbounded recursion: rule 'A' can never end (A -> B -> A)"},
        {"CycleBelowTheAxiom",
         "Lot -> Extrude(3) { A, NULL };\nA -> Translate(0, 0, 1) { B };\nB -> Translate(0, 0, 1) { A };\n",
         "bad.grammar:2:1", "unbounded recursion: rule 'A' can never end (A -> B -> A)"},
        // A rule that merely leads into a cycle must not report the same cycle again.
        {"CycleReachedFromALaterRule",
         "A -> Translate(0, 0, 1) { B };\nB -> Translate(0, 0, 1) { A };\nC -> Extrude(3) { A, NULL };\n",
         "bad.grammar:1:1", "(A -> B -> A)"},
        // Split hands its scope to every part, so one ending part does not end the recursion.
        {"CycleThroughSplit", "A -> Split(x, ~1, ~1) { NULL, A };\n", "bad.grammar:1:1",
         "unbounded recursion: rule 'A' can never end (A -> A)"},

        // --- Types --------------------------------------------------------------------
        {"CondOnNumber", "A -> Cond(width) { NULL };\n", "bad.grammar:1:11",
         "type error: the condition of Cond needs a boolean, found a number"},
        // A binary expression is located at its operator (here the '>').
        {"ExtrudeOnBoolean", "A -> Extrude(width > 3) { NULL, NULL };\n", "bad.grammar:1:20",
         "type error: argument 1 of Extrude needs a number, found a boolean"},
        {"AndOnNumbers", "A -> Cond(1 && 2) { NULL };\n", "bad.grammar:1:11",
         "type error: operator '&&' needs a boolean, found a number"},
        {"EqualityNumberBoolean", "A -> Cond(width == true) { NULL };\n", "bad.grammar:1:20",
         "type error: the right side of '==' needs a number, found a boolean"},
        {"NotOnNumber", "A -> Cond(!3) { NULL };\n", "bad.grammar:1:12",
         "type error: '!' needs a boolean, found a number"},
        {"TernaryBranchesDiffer", "A -> Cond(true ? 1 : false) { NULL };\n", "bad.grammar:1:22",
         "type error: the second branch of '?:' needs a number, found a boolean"},

        // --- Declarations -------------------------------------------------------------
        {"DuplicateRule", "A -> NULL;\nA -> NULL;\n", "bad.grammar:2:1",
         "rule 'A' is defined twice (first at line 1)"},
        {"DuplicateParameter", "param h = 3 in [1, 5];\nparam h = 3 in [1, 5];\nA -> NULL;\n",
         "bad.grammar:2:7", "parameter 'h' is declared twice (first at line 1)"},
        {"DefaultOutOfRange", "param h = 7 in [1, 5];\nA -> NULL;\n", "bad.grammar:1:7",
         "the default of parameter 'h' lies outside its range"},
        {"EmptyRange", "param h = 3 in [5, 1];\nA -> NULL;\n", "bad.grammar:1:7",
         "parameter 'h' has an empty range"},
        {"ParameterNamedLikeAccessor", "param width = 3 in [1, 5];\nA -> NULL;\n", "bad.grammar:1:7",
         "parameter 'width' would hide the accessor or function of that name"},
        {"ParameterNamedLikeFunction", "param min = 3 in [1, 5];\nA -> NULL;\n", "bad.grammar:1:7",
         "parameter 'min' would hide the accessor or function of that name"},
        {"ShapeZeroTriangles", "shape w(triangles = 0);\nA -> NULL;\n", "bad.grammar:1:9",
         "shape field 'triangles' must be a whole number in [1, 1e6]"},
        {"ShapeFractionalTriangles", "shape w(triangles = 2.5);\nA -> NULL;\n", "bad.grammar:1:9",
         "shape field 'triangles' must be a whole number"},
        {"ShapeNegativeWidth", "shape w(width = -1, triangles = 2);\nA -> NULL;\n", "bad.grammar:1:9",
         "shape field 'width' must be in (0, 1e5) metres"},
        {"ShapeUnknownField", "shape w(colour = 1, triangles = 2);\nA -> NULL;\n", "bad.grammar:1:9",
         "unknown shape field 'colour'"},
        {"ShapeWithoutTriangles", "shape w(width = 1);\nA -> NULL;\n", "bad.grammar:1:7",
         "shape 'w' needs a triangle count (triangles = N)"},
        {"DuplicateShape", "shape w(triangles = 2);\nshape w(triangles = 3);\nA -> NULL;\n",
         "bad.grammar:2:7", "shape 'w' is declared twice"},
        {"EmptyGrammar", "", "bad.grammar:1:1", "the grammar has no rules"},
        {"OnlyDeclarations", "# parameters but no rules\nparam h = 3 in [1, 5];\n", "bad.grammar:1:1",
         "the grammar has no rules"},

        // --- Limits -------------------------------------------------------------------
        // 40 nested parentheses: the parser stops at the one that crosses its nesting cap
        // (64 levels, two per parenthesis: expression and operand).
        {"ExpressionNestedTooDeeply",
         "A -> Extrude(" + repeated("(", 40) + "1" + repeated(")", 40) + ") { NULL, NULL };\n",
         "bad.grammar:1:47", "expression nested too deeply"},
        // 17 chained '?:' keep every else-branch on the evaluation stack: 34 slots > 32.
        {"ExpressionTooComplex", "A -> Extrude(" + repeated("true ? 1 : ", 17) + "2) { NULL, NULL };\n",
         "bad.grammar:1:195", "expression is too complex to evaluate"},
        // 2049 terms make 4097 nodes, one more than the cap; the node that crosses it is the
        // sum at the 2048th '+' (column 13 + 2 * 2048).
        {"ExpressionTooLong", "A -> Extrude(1" + repeated("+1", 2048) + ") { NULL, NULL };\n",
         "bad.grammar:1:4109", "expression is too long"},
    };
    return cases;
}

class BadGrammarTest : public ::testing::TestWithParam<BadGrammar> {};

TEST_P(BadGrammarTest, ReportsTheErrorWhereTheUserLooks) {
    const BadGrammar& c = GetParam();
    DiagnosticList diagnostics;
    const CompiledGrammar g = compileGrammar(c.source, "bad.grammar", diagnostics);
    ASSERT_TRUE(diagnostics.hasErrors()) << "compiled without error:\n" << c.source;
    // Documented: on any error the returned grammar is empty, so nothing can expand it.
    EXPECT_TRUE(g.rules.empty());

    std::vector<std::string> errors;
    for (const Diagnostic& d : diagnostics.all()) {
        if (d.severity == Severity::Error) errors.push_back(formatDiagnostic(d));
    }
    ASSERT_FALSE(errors.empty());
    const std::string prefix = c.location + ": error: ";
    EXPECT_EQ(errors.front().substr(0, prefix.size()), prefix) << diagnostics.formatAll();
    EXPECT_NE(errors.front().find(c.message), std::string::npos) << "expected \"" << c.message << "\" in:\n"
                                                                 << diagnostics.formatAll();
    EXPECT_EQ(errors.size(), c.errors) << diagnostics.formatAll();
}

INSTANTIATE_TEST_SUITE_P(Table, BadGrammarTest, ::testing::ValuesIn(badGrammars()),
                         [](const ::testing::TestParamInfo<BadGrammar>& info) { return info.param.name; });

TEST(BadGrammarTableTest, CoversAtLeastTwentyFourCasesWithUniqueNames) {
    const std::vector<BadGrammar> cases = badGrammars();
    EXPECT_GE(cases.size(), 24u);
    std::set<std::string> names;
    for (const BadGrammar& c : cases) EXPECT_TRUE(names.insert(c.name).second) << c.name;
}

std::vector<std::string> errorLines(const std::string& source) {
    DiagnosticList diagnostics;
    compileGrammar(source, "bad.grammar", diagnostics);
    std::vector<std::string> lines;
    for (const Diagnostic& d : diagnostics.all()) {
        if (d.severity == Severity::Error) lines.push_back(formatDiagnostic(d));
    }
    return lines;
}

// Parser recovery: an error abandons only its own statement, so a second, independent
// mistake further down is reported in the same run.
TEST(BadGrammarRecoveryTest, TwoSyntaxErrorsOnDifferentLinesAreBothReported) {
    const std::vector<std::string> errors = errorLines("A -> Extrude(3 { NULL, NULL };\n"
                                                       "B -> NULL;\n"
                                                       "C -> Split(x, 1 2) { NULL, NULL };\n"
                                                       "D -> NULL;\n");
    ASSERT_EQ(errors.size(), 2u);
    EXPECT_EQ(errors[0].rfind("bad.grammar:1:16: error: expected ')'", 0), 0u) << errors[0];
    EXPECT_EQ(errors[1].rfind("bad.grammar:3:17: error: expected ')'", 0), 0u) << errors[1];
}

TEST(BadGrammarRecoveryTest, TwoRuleErrorsOnDifferentLinesAreBothReported) {
    const std::vector<std::string> errors = errorLines("A -> Extrud(3) { B, B };\n"
                                                       "B -> NULL;\n"
                                                       "C -> Translate(0, 0) { NULL };\n");
    ASSERT_EQ(errors.size(), 2u);
    EXPECT_EQ(errors[0].rfind("bad.grammar:1:6: error: unknown rule operation 'Extrud'", 0), 0u) << errors[0];
    EXPECT_EQ(errors[1].rfind("bad.grammar:3:6: error: wrong number of arguments to Translate", 0), 0u)
        << errors[1];
}

// The most common slip, a forgotten ';', must not swallow the next statement: its own
// mistake (the unclosed call on line 2) is a second, independent error.
TEST(BadGrammarRecoveryTest, MissingSemicolonDoesNotHideTheNextStatementsError) {
    const std::vector<std::string> errors = errorLines("A -> Extrude(3) { B, B }\n"
                                                       "B -> Extrude(3 { NULL, NULL };\n");
    ASSERT_EQ(errors.size(), 2u) << ::testing::PrintToString(errors);
    EXPECT_NE(errors[0].find("expected ';' after the rule 'A'"), std::string::npos) << errors[0];
    EXPECT_EQ(errors[1].rfind("bad.grammar:2:16: error: expected ')'", 0), 0u) << errors[1];
}

// Near misses that are valid: the checks above must not reject them.
TEST(BadGrammarNearMissTest, ValidGrammarsCloseToTheBadOnesCompile) {
    const char* const valid[] = {
        // A one-successor Cond drops the scope when false, so this recursion can end.
        "A -> Cond(depth < 10) { B };\nB -> Translate(0, 0, 1) { A };\n",
        "A -> Cond(depth < 10) { B, NULL };\nB -> Translate(0, 0, 1) { A };\n",
        "A -> Choose(1: B, 1: NULL);\nB -> Branch(2) { A };\n",
        "A -> Split(x, ~1, 2, ~1) { NULL, NULL, NULL };\n",
        "A -> Cond(width == 3 == true) { NULL };\n",
        "// a comment\nA -> NULL; # no newline at the end",
        "param w_ = 1 in [1, 1];\nA -> Extrude(w_ * -2 + 3e0 + .5 + 2.) { NULL, NULL };\n",
    };
    for (const char* source : valid) {
        EXPECT_EQ(hexlod::test::compileErrors(source, "ok.grammar"), "") << source;
    }
}

} // namespace
} // namespace hexlod::grammar
