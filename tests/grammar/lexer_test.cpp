#include "hexlod/grammar/lexer.h"

#include <gtest/gtest.h>

namespace hexlod::grammar {
namespace {

std::vector<Token> lex(std::string_view text, DiagnosticList& diagnostics) {
    return tokenize(text, "lex.grammar", diagnostics);
}

TEST(Lexer, TokensCarryLineAndColumn) {
    DiagnosticList d;
    const auto tokens = lex("A -> Split(x, ~1.5e1)\n  { B };", d);
    ASSERT_FALSE(d.hasErrors());
    const TokenKind expected[] = {TokenKind::Identifier, TokenKind::Arrow,      TokenKind::Identifier,
                                  TokenKind::LParen,     TokenKind::Identifier, TokenKind::Comma,
                                  TokenKind::Tilde,      TokenKind::Number,     TokenKind::RParen,
                                  TokenKind::LBrace,     TokenKind::Identifier, TokenKind::RBrace,
                                  TokenKind::Semicolon,  TokenKind::End};
    ASSERT_EQ(tokens.size(), std::size(expected));
    for (size_t i = 0; i < tokens.size(); ++i) EXPECT_EQ(tokens[i].kind, expected[i]) << i;
    EXPECT_DOUBLE_EQ(tokens[7].number, 15.0);
    EXPECT_EQ(tokens[7].column, 16u);
    EXPECT_EQ(tokens[9].line, 2u);
    EXPECT_EQ(tokens[9].column, 3u);
}

TEST(Lexer, CommentsAndTwoCharacterOperators) {
    DiagnosticList d;
    const auto tokens = lex("# a comment\na <= b // another\n&& !c != d || e >= f == g", d);
    ASSERT_FALSE(d.hasErrors());
    std::vector<TokenKind> kinds;
    for (const Token& t : tokens) kinds.push_back(t.kind);
    const std::vector<TokenKind> expected = {
        TokenKind::Identifier, TokenKind::LessEqual,  TokenKind::Identifier,   TokenKind::AndAnd,
        TokenKind::Bang,       TokenKind::Identifier, TokenKind::NotEqual,     TokenKind::Identifier,
        TokenKind::OrOr,       TokenKind::Identifier, TokenKind::GreaterEqual, TokenKind::Identifier,
        TokenKind::EqualEqual, TokenKind::Identifier, TokenKind::End};
    EXPECT_EQ(kinds, expected);
    EXPECT_EQ(tokens[0].line, 2u);
}

TEST(Lexer, BadCharactersAndNumbersAreReportedAndSkipped) {
    DiagnosticList d;
    const auto tokens = lex("a $ 1.2.3 b", d);
    ASSERT_EQ(d.all().size(), 2u);
    EXPECT_EQ(formatDiagnostic(d.all()[0]), "lex.grammar:1:3: error: unexpected character '$'");
    EXPECT_EQ(formatDiagnostic(d.all()[1]), "lex.grammar:1:5: error: malformed number '1.2.3'");
    EXPECT_EQ(tokens.back().kind, TokenKind::End);
    EXPECT_EQ(tokens[tokens.size() - 2].text, "b");
}

TEST(Lexer, NonPrintableBytesAreNamedByValue) {
    DiagnosticList d;
    lex(std::string_view("a\x01", 2), d);
    ASSERT_EQ(d.all().size(), 1u);
    EXPECT_NE(d.all()[0].message.find("0x1"), std::string::npos);
}

} // namespace
} // namespace hexlod::grammar
