#include "hexlod/grammar/lexer.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>

namespace hexlod::grammar {

const char* tokenKindName(TokenKind kind) {
    switch (kind) {
    case TokenKind::Identifier:
        return "identifier";
    case TokenKind::Number:
        return "number";
    case TokenKind::Arrow:
        return "'->'";
    case TokenKind::LParen:
        return "'('";
    case TokenKind::RParen:
        return "')'";
    case TokenKind::LBrace:
        return "'{'";
    case TokenKind::RBrace:
        return "'}'";
    case TokenKind::LBracket:
        return "'['";
    case TokenKind::RBracket:
        return "']'";
    case TokenKind::Comma:
        return "','";
    case TokenKind::Semicolon:
        return "';'";
    case TokenKind::Colon:
        return "':'";
    case TokenKind::Tilde:
        return "'~'";
    case TokenKind::Plus:
        return "'+'";
    case TokenKind::Minus:
        return "'-'";
    case TokenKind::Star:
        return "'*'";
    case TokenKind::Slash:
        return "'/'";
    case TokenKind::Percent:
        return "'%'";
    case TokenKind::Less:
        return "'<'";
    case TokenKind::LessEqual:
        return "'<='";
    case TokenKind::Greater:
        return "'>'";
    case TokenKind::GreaterEqual:
        return "'>='";
    case TokenKind::EqualEqual:
        return "'=='";
    case TokenKind::NotEqual:
        return "'!='";
    case TokenKind::Assign:
        return "'='";
    case TokenKind::AndAnd:
        return "'&&'";
    case TokenKind::OrOr:
        return "'||'";
    case TokenKind::Bang:
        return "'!'";
    case TokenKind::Question:
        return "'?'";
    case TokenKind::End:
        return "end of file";
    }
    return "token";
}

namespace {

bool isIdentStart(char c) {
    return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool isIdentChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}
bool isDigit(char c) {
    return c >= '0' && c <= '9';
}

struct TwoCharToken {
    char first, second;
    TokenKind kind;
};
constexpr TwoCharToken kTwoCharTokens[] = {
    {'-', '>', TokenKind::Arrow},      {'<', '=', TokenKind::LessEqual}, {'>', '=', TokenKind::GreaterEqual},
    {'=', '=', TokenKind::EqualEqual}, {'!', '=', TokenKind::NotEqual},  {'&', '&', TokenKind::AndAnd},
    {'|', '|', TokenKind::OrOr},
};

bool singleCharToken(char c, TokenKind& kind) {
    switch (c) {
    case '(':
        kind = TokenKind::LParen;
        return true;
    case ')':
        kind = TokenKind::RParen;
        return true;
    case '{':
        kind = TokenKind::LBrace;
        return true;
    case '}':
        kind = TokenKind::RBrace;
        return true;
    case '[':
        kind = TokenKind::LBracket;
        return true;
    case ']':
        kind = TokenKind::RBracket;
        return true;
    case ',':
        kind = TokenKind::Comma;
        return true;
    case ';':
        kind = TokenKind::Semicolon;
        return true;
    case ':':
        kind = TokenKind::Colon;
        return true;
    case '~':
        kind = TokenKind::Tilde;
        return true;
    case '+':
        kind = TokenKind::Plus;
        return true;
    case '-':
        kind = TokenKind::Minus;
        return true;
    case '*':
        kind = TokenKind::Star;
        return true;
    case '/':
        kind = TokenKind::Slash;
        return true;
    case '%':
        kind = TokenKind::Percent;
        return true;
    case '<':
        kind = TokenKind::Less;
        return true;
    case '>':
        kind = TokenKind::Greater;
        return true;
    case '=':
        kind = TokenKind::Assign;
        return true;
    case '!':
        kind = TokenKind::Bang;
        return true;
    case '?':
        kind = TokenKind::Question;
        return true;
    default:
        return false;
    }
}

} // namespace

std::vector<Token> tokenize(std::string_view source, const std::string& fileName,
                            DiagnosticList& diagnostics) {
    std::vector<Token> tokens;
    size_t i = 0;
    uint32_t line = 1, column = 1;
    auto advance = [&](size_t n) {
        for (size_t k = 0; k < n && i < source.size(); ++k, ++i) {
            if (source[i] == '\n') {
                ++line;
                column = 1;
            } else {
                ++column;
            }
        }
    };
    while (i < source.size()) {
        const char c = source[i];
        if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
            advance(1);
            continue;
        }
        if (c == '#' || (c == '/' && i + 1 < source.size() && source[i + 1] == '/')) {
            while (i < source.size() && source[i] != '\n') advance(1);
            continue;
        }
        Token token;
        token.line = line;
        token.column = column;
        const size_t start = i;
        if (isIdentStart(c)) {
            size_t end = i;
            while (end < source.size() && isIdentChar(source[end])) ++end;
            token.kind = TokenKind::Identifier;
            token.text = source.substr(start, end - start);
            advance(end - start);
            tokens.push_back(token);
            continue;
        }
        if (isDigit(c) || (c == '.' && i + 1 < source.size() && isDigit(source[i + 1]))) {
            size_t end = i;
            while (end < source.size() && (isDigit(source[end]) || source[end] == '.')) ++end;
            // An exponent marker belongs to the number even without digits, so "1.5e" is one
            // malformed number rather than 1.5 followed by a name 'e'.
            if (end < source.size() && (source[end] == 'e' || source[end] == 'E')) {
                ++end;
                if (end < source.size() && (source[end] == '+' || source[end] == '-')) ++end;
                while (end < source.size() && isDigit(source[end])) ++end;
            }
            token.kind = TokenKind::Number;
            token.text = source.substr(start, end - start);
            const auto [ptr, ec] = std::from_chars(source.data() + start, source.data() + end, token.number);
            // Values are evaluated as 32-bit floats, so anything beyond their range is an error
            // here rather than a silent infinity later.
            if (ec == std::errc::result_out_of_range ||
                (ec == std::errc() && std::fabs(token.number) > std::numeric_limits<float>::max())) {
                diagnostics.error({fileName, line, column}, "number '" + std::string(token.text) +
                                                                "' is out of range (at most about 3.4e38)");
                token.number = 0.0;
            } else if (ec != std::errc() || ptr != source.data() + end) {
                diagnostics.error({fileName, line, column},
                                  "malformed number '" + std::string(token.text) + "'");
                token.number = 0.0;
            }
            advance(end - start);
            tokens.push_back(token);
            continue;
        }
        bool matched = false;
        if (i + 1 < source.size()) {
            for (const TwoCharToken& two : kTwoCharTokens) {
                if (c == two.first && source[i + 1] == two.second) {
                    token.kind = two.kind;
                    token.text = source.substr(start, 2);
                    advance(2);
                    tokens.push_back(token);
                    matched = true;
                    break;
                }
            }
        }
        if (matched) continue;
        if (singleCharToken(c, token.kind)) {
            token.text = source.substr(start, 1);
            advance(1);
            tokens.push_back(token);
            continue;
        }
        const unsigned char byte = static_cast<unsigned char>(c);
        diagnostics.error({fileName, line, column},
                          std::isprint(byte) ? "unexpected character '" + std::string(1, c) + "'"
                                             : "unexpected byte 0x" + std::to_string(static_cast<int>(byte)));
        advance(1);
    }
    Token end;
    end.kind = TokenKind::End;
    end.line = line;
    end.column = column;
    tokens.push_back(end);
    return tokens;
}

} // namespace hexlod::grammar
