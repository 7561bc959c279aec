#include "hexlod/grammar/diagnostics.h"

#include <algorithm>
#include <tuple>

namespace hexlod::grammar {

std::string formatDiagnostic(const Diagnostic& diagnostic) {
    std::string out;
    if (!diagnostic.location.file.empty() || diagnostic.location.line > 0) {
        out += diagnostic.location.file.empty() ? "<input>" : diagnostic.location.file;
        out += ':' + std::to_string(diagnostic.location.line) + ':' +
               std::to_string(diagnostic.location.column) + ": ";
    }
    out += diagnostic.severity == Severity::Error ? "error: " : "warning: ";
    out += diagnostic.message;
    return out;
}

void DiagnosticList::error(const SourceLocation& where, std::string message) {
    items_.push_back({Severity::Error, where, std::move(message)});
    ++errorCount_;
}

void DiagnosticList::warning(const SourceLocation& where, std::string message) {
    items_.push_back({Severity::Warning, where, std::move(message)});
}

void DiagnosticList::sortByLocation() {
    std::stable_sort(items_.begin(), items_.end(), [](const Diagnostic& a, const Diagnostic& b) {
        return std::tie(a.location.line, a.location.column) < std::tie(b.location.line, b.location.column);
    });
}

std::string DiagnosticList::formatAll() const {
    std::string out;
    for (const Diagnostic& d : items_) out += formatDiagnostic(d) + '\n';
    return out;
}

} // namespace hexlod::grammar
