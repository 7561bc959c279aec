// Lexer for the hexlod split-grammar language (docs/grammar.md).
#pragma once

#include "hexlod/grammar/diagnostics.h"

#include <string>
#include <string_view>
#include <vector>

namespace hexlod::grammar {

enum class TokenKind : uint8_t {
    Identifier,
    Number,
    Arrow,     // ->
    LParen,    // (
    RParen,    // )
    LBrace,    // {
    RBrace,    // }
    LBracket,  // [
    RBracket,  // ]
    Comma,     // ,
    Semicolon, // ;
    Colon,     // :
    Tilde,     // ~
    Plus,
    Minus,
    Star,
    Slash,
    Percent,
    Less,
    LessEqual,
    Greater,
    GreaterEqual,
    EqualEqual,
    NotEqual,
    Assign, // =
    AndAnd,
    OrOr,
    Bang,
    Question,
    End,
};

const char* tokenKindName(TokenKind kind);

struct Token {
    TokenKind kind = TokenKind::End;
    std::string_view text; // view into the source handed to tokenize()
    double number = 0.0;
    uint32_t line = 1;
    uint32_t column = 1;
};

// Splits `source` into tokens. Comments run from `#` or `//` to the end of the line.
// Unknown characters and malformed numbers are reported and skipped, so the parser
// still sees the rest of the file and can report further errors.
std::vector<Token> tokenize(std::string_view source, const std::string& fileName,
                            DiagnosticList& diagnostics);

} // namespace hexlod::grammar
