// Diagnostics shared by the grammar front end and the expander.
// Every message a user sees carries file:line:col so that an editor can jump to it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace hexlod::grammar {

struct SourceLocation {
    std::string file;
    uint32_t line = 0;   // 1-based; 0 means "no location"
    uint32_t column = 0; // 1-based
};

enum class Severity : uint8_t { Warning, Error };

struct Diagnostic {
    Severity severity = Severity::Error;
    SourceLocation location;
    std::string message;
};

// "file:line:col: error: message", the format compilers use and editors parse.
std::string formatDiagnostic(const Diagnostic& diagnostic);

class DiagnosticList {
public:
    void error(const SourceLocation& where, std::string message);
    void warning(const SourceLocation& where, std::string message);
    bool hasErrors() const { return errorCount_ > 0; }
    const std::vector<Diagnostic>& all() const { return items_; }
    std::string formatAll() const;
    // Lexer and parser report in two passes; users read errors in file order.
    void sortByLocation();

private:
    std::vector<Diagnostic> items_;
    size_t errorCount_ = 0;
};

} // namespace hexlod::grammar
