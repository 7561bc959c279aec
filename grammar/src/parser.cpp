#include "hexlod/grammar/parser.h"

#include <cmath>
#include <stdexcept>

namespace hexlod::grammar {
namespace {

// Thrown to abandon the current statement; caught at statement level, which skips to ';'.
struct ParseError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

constexpr int kMaxExpressionNesting = 64;
// Long operator chains are parsed iteratively but still form deep trees; capping the node
// count keeps the compiler's recursion and memory bounded on hostile input.
constexpr int kMaxExpressionNodes = 4096;

class Parser {
public:
    Parser(std::vector<Token> tokens, const std::string& fileName, DiagnosticList& diagnostics)
        : tokens_(std::move(tokens)), fileName_(fileName), diagnostics_(diagnostics) {}

    GrammarAst parse() {
        GrammarAst ast;
        ast.fileName = fileName_;
        while (peek().kind != TokenKind::End) {
            try {
                statement(ast);
            } catch (const ParseError&) {
                recover();
            }
        }
        return ast;
    }

private:
    const Token& peek(size_t ahead = 0) const {
        const size_t index = std::min(position_ + ahead, tokens_.size() - 1);
        return tokens_[index];
    }
    const Token& next() {
        const Token& token = tokens_[position_];
        if (position_ + 1 < tokens_.size()) ++position_;
        return token;
    }
    bool accept(TokenKind kind) {
        if (peek().kind != kind) return false;
        next();
        return true;
    }
    SourceLocation locationOf(const Token& token) const { return {fileName_, token.line, token.column}; }

    [[noreturn]] void fail(const Token& at, const std::string& message) {
        diagnostics_.error(locationOf(at), message);
        throw ParseError(message);
    }
    std::string describe(const Token& token) const {
        if (token.kind == TokenKind::End) return "end of file";
        return "'" + std::string(token.text) + "'";
    }
    const Token& expect(TokenKind kind, const std::string& context) {
        if (peek().kind != kind) {
            fail(peek(), std::string("expected ") + tokenKindName(kind) + " " + context + ", found " +
                             describe(peek()));
        }
        return next();
    }

    // A ';' forgotten at the end of a line is reported just after the statement, where the
    // user forgot it, and parsing goes on: the next line is usually a whole statement with its
    // own errors. Anything else on the same line is an unexpected token, reported where it is.
    void endStatement(const std::string& context) {
        if (accept(TokenKind::Semicolon)) return;
        const Token& last = tokens_[position_ > 0 ? position_ - 1 : 0];
        if (peek().kind != TokenKind::End && peek().line == last.line) {
            fail(peek(), "expected ';' " + context + ", found " + describe(peek()));
        }
        const uint32_t width = static_cast<uint32_t>(last.text.size());
        diagnostics_.error({fileName_, last.line, last.column + width}, "expected ';' " + context);
    }

    // Skips to just after the next ';' (or to a '}' ending a successor block at statement level).
    void recover() {
        while (peek().kind != TokenKind::End) {
            if (next().kind == TokenKind::Semicolon) return;
        }
    }

    void statement(GrammarAst& ast) {
        const Token& head = peek();
        if (head.kind != TokenKind::Identifier) {
            fail(head,
                 "expected a declaration (param, shape, extruded_set or a rule), found " + describe(head));
        }
        if (head.text == "param" && peek(1).kind == TokenKind::Identifier) return paramDecl(ast);
        if (head.text == "shape" && peek(1).kind == TokenKind::Identifier) return shapeDecl(ast);
        if (head.text == "extruded_set" && peek(1).kind == TokenKind::Identifier) return extrudedDecl(ast);
        ruleDecl(ast);
    }

    double signedNumber(const char* context) {
        const bool negative = accept(TokenKind::Minus);
        const Token& token = expect(TokenKind::Number, context);
        return negative ? -token.number : token.number;
    }

    // param NAME = default in [min, max];
    void paramDecl(GrammarAst& ast) {
        next();
        const Token& name = next();
        ParamDecl param;
        param.name = std::string(name.text);
        param.location = locationOf(name);
        expect(TokenKind::Assign, "after the parameter name");
        param.defaultValue = signedNumber("as the parameter's default value");
        const Token& in = peek();
        if (in.kind != TokenKind::Identifier || in.text != "in") {
            fail(in, "expected 'in [min, max]' after the default of parameter '" + param.name + "'");
        }
        next();
        expect(TokenKind::LBracket, "to open the parameter range");
        param.minValue = signedNumber("as the range minimum");
        expect(TokenKind::Comma, "between the range bounds");
        param.maxValue = signedNumber("as the range maximum");
        expect(TokenKind::RBracket, "to close the parameter range");
        endStatement("after the parameter declaration");
        ast.params.push_back(std::move(param));
    }

    // shape NAME(width = 1, height = 2, depth = 0.3, depth_ratio = 0.2, triangles = 120);
    void shapeDecl(GrammarAst& ast) {
        next();
        const Token& name = next();
        ShapeDeclAst shape;
        shape.name = std::string(name.text);
        shape.location = locationOf(name);
        expect(TokenKind::LParen, "after the shape name");
        if (peek().kind != TokenKind::RParen) {
            do {
                const Token& field = expect(TokenKind::Identifier, "as a shape field name");
                expect(TokenKind::Assign, "after the shape field name");
                const double value = signedNumber("as the shape field value");
                shape.fields.push_back({std::string(field.text), value, locationOf(field)});
            } while (accept(TokenKind::Comma));
        }
        expect(TokenKind::RParen, "to close the shape declaration");
        endStatement("after the shape declaration");
        ast.shapes.push_back(std::move(shape));
    }

    // extruded_set A, B;
    void extrudedDecl(GrammarAst& ast) {
        const Token& keyword = next();
        if (ast.hasExtrudedDirective) {
            diagnostics_.error(locationOf(keyword), "extruded_set is declared twice");
        }
        ast.hasExtrudedDirective = true;
        do {
            const Token& name = expect(TokenKind::Identifier, "as a rule name in extruded_set");
            ast.extrudedStops.push_back({std::string(name.text), locationOf(name)});
        } while (accept(TokenKind::Comma));
        endStatement("after extruded_set");
    }

    // Name -> Operation(args) { successors };
    void ruleDecl(GrammarAst& ast) {
        const Token& name = next();
        RuleDecl rule;
        rule.name = std::string(name.text);
        rule.location = locationOf(name);
        expect(TokenKind::Arrow, "after the rule name '" + rule.name + "'");
        const Token& operation = expect(TokenKind::Identifier, "as the rule operation");
        rule.operation = std::string(operation.text);
        rule.operationLocation = locationOf(operation);
        if (accept(TokenKind::LParen)) {
            if (peek().kind != TokenKind::RParen) {
                do {
                    rule.arguments.push_back(argument());
                } while (accept(TokenKind::Comma));
            }
            expect(TokenKind::RParen, "to close the argument list of " + rule.operation);
        }
        if (accept(TokenKind::LBrace)) {
            rule.hasSuccessorBlock = true;
            if (peek().kind != TokenKind::RBrace) {
                do {
                    const Token& successor = expect(TokenKind::Identifier, "as a successor rule name");
                    rule.successors.push_back({std::string(successor.text), locationOf(successor)});
                } while (accept(TokenKind::Comma));
            }
            expect(TokenKind::RBrace, "to close the successor list");
        }
        endStatement("after the rule '" + rule.name + "'");
        ast.rules.push_back(std::move(rule));
    }

    RuleArgument argument() {
        RuleArgument arg;
        expressionNodes_ = 0;
        arg.relativeLocation = locationOf(peek());
        arg.relative = accept(TokenKind::Tilde);
        arg.value = expression(0);
        if (accept(TokenKind::Colon)) {
            const Token& label = expect(TokenKind::Identifier, "as the successor after ':'");
            arg.label = std::string(label.text);
            arg.labelLocation = locationOf(label);
        }
        return arg;
    }

    ExprPtr node(ExprNode::Kind kind, const Token& at) {
        if (++expressionNodes_ > kMaxExpressionNodes) fail(at, "expression is too long");
        auto n = std::make_unique<ExprNode>();
        n->kind = kind;
        n->location = locationOf(at);
        return n;
    }

    void checkNesting(int nesting, const Token& at) {
        if (nesting > kMaxExpressionNesting) fail(at, "expression nested too deeply");
    }

    ExprPtr expression(int nesting) {
        checkNesting(nesting, peek());
        ExprPtr condition = binary(0, nesting);
        if (peek().kind != TokenKind::Question) return condition;
        const Token& question = next();
        ExprPtr ternary = node(ExprNode::Kind::Ternary, question);
        ternary->children.push_back(std::move(condition));
        ternary->children.push_back(expression(nesting + 1));
        expect(TokenKind::Colon, "in the conditional expression");
        ternary->children.push_back(expression(nesting + 1));
        return ternary;
    }

    static int precedence(TokenKind kind) {
        switch (kind) {
        case TokenKind::OrOr:
            return 1;
        case TokenKind::AndAnd:
            return 2;
        case TokenKind::EqualEqual:
        case TokenKind::NotEqual:
            return 3;
        case TokenKind::Less:
        case TokenKind::LessEqual:
        case TokenKind::Greater:
        case TokenKind::GreaterEqual:
            return 4;
        case TokenKind::Plus:
        case TokenKind::Minus:
            return 5;
        case TokenKind::Star:
        case TokenKind::Slash:
        case TokenKind::Percent:
            return 6;
        default:
            return 0;
        }
    }

    // Precedence climbing over the left-associative binary operators.
    ExprPtr binary(int minPrecedence, int nesting) {
        ExprPtr left = unary(nesting + 1);
        while (true) {
            const int prec = precedence(peek().kind);
            if (prec == 0 || prec <= minPrecedence) return left;
            const Token& op = next();
            checkNesting(nesting + 1, op);
            ExprPtr right = binary(prec, nesting + 1);
            ExprPtr combined = node(ExprNode::Kind::Binary, op);
            combined->op = op.kind;
            combined->children.push_back(std::move(left));
            combined->children.push_back(std::move(right));
            left = std::move(combined);
        }
    }

    ExprPtr unary(int nesting) {
        const Token& token = peek();
        if (token.kind == TokenKind::Minus || token.kind == TokenKind::Bang ||
            token.kind == TokenKind::Plus) {
            next();
            checkNesting(nesting + 1, token);
            ExprPtr operand = unary(nesting + 1);
            if (token.kind == TokenKind::Plus) return operand;
            ExprPtr n = node(ExprNode::Kind::Unary, token);
            n->op = token.kind;
            n->children.push_back(std::move(operand));
            return n;
        }
        return primary(nesting);
    }

    ExprPtr primary(int nesting) {
        const Token& token = peek();
        if (token.kind == TokenKind::Number) {
            next();
            ExprPtr n = node(ExprNode::Kind::Number, token);
            n->number = token.number;
            return n;
        }
        if (token.kind == TokenKind::Identifier) {
            next();
            if (accept(TokenKind::LParen)) {
                ExprPtr call = node(ExprNode::Kind::Call, token);
                call->name = std::string(token.text);
                if (peek().kind != TokenKind::RParen) {
                    do {
                        call->children.push_back(expression(nesting + 1));
                    } while (accept(TokenKind::Comma));
                }
                expect(TokenKind::RParen, "to close the call of " + call->name);
                return call;
            }
            ExprPtr n = node(ExprNode::Kind::Name, token);
            n->name = std::string(token.text);
            return n;
        }
        if (token.kind == TokenKind::LParen) {
            next();
            ExprPtr inner = expression(nesting + 1);
            expect(TokenKind::RParen, "to close the parenthesis");
            return inner;
        }
        fail(token, "expected an expression, found " + describe(token));
    }

    std::vector<Token> tokens_;
    size_t position_ = 0;
    int expressionNodes_ = 0;
    const std::string& fileName_;
    DiagnosticList& diagnostics_;
};

} // namespace

GrammarAst parseGrammar(std::string_view source, const std::string& fileName, DiagnosticList& diagnostics) {
    std::vector<Token> tokens = tokenize(source, fileName, diagnostics);
    Parser parser(std::move(tokens), fileName, diagnostics);
    GrammarAst ast = parser.parse();
    diagnostics.sortByLocation();
    return ast;
}

} // namespace hexlod::grammar
