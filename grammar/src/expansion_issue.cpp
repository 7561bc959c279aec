#include "hexlod/grammar/expander.h"

namespace hexlod::grammar {

const char* issueKindName(IssueKind kind) {
    switch (kind) {
    case IssueKind::DepthCap:
        return "recursion depth cap reached; the branch was cut";
    case IssueKind::AtomTerminalCap:
        return "terminal cap per atom reached; the atom's terminals were dropped";
    case IssueKind::AtomOperationCap:
        return "work cap per atom reached; the atom's terminals were dropped";
    case IssueKind::BatchTerminalCap:
        return "terminal cap per batch reached; the batch was not generated";
    case IssueKind::InvalidSize:
        return "size is NaN, infinite or negative";
    case IssueKind::TooManyTiles:
        return "Repeat would exceed the work cap; the scope was dropped";
    case IssueKind::InvalidCount:
        return "Branch count is NaN, negative or above 1024; the scope was dropped";
    case IssueKind::InvalidProbability:
        return "Choose probabilities are NaN, negative or sum to 0; the scope was dropped";
    case IssueKind::InvalidTransform:
        return "Translate or Rotate amount is NaN or infinite; the scope was dropped";
    case IssueKind::WrongScopeKind:
        return "operation does not apply to this kind of scope; the scope was dropped";
    case IssueKind::DegenerateFootprint:
        return "footprint is unusable; the building was skipped";
    case IssueKind::SelfIntersectingFootprint:
        return "footprint intersects itself; expanded edge by edge anyway";
    case IssueKind::DuplicateBuilding:
        return "building id appears more than once; later copies were skipped";
    case IssueKind::BadParameters:
        return "parameter vector does not match the grammar; defaults were used";
    }
    return "unknown issue";
}

bool issueIsError(IssueKind kind) {
    return kind == IssueKind::AtomTerminalCap || kind == IssueKind::AtomOperationCap ||
           kind == IssueKind::BatchTerminalCap || kind == IssueKind::DepthCap ||
           kind == IssueKind::TooManyTiles || kind == IssueKind::DegenerateFootprint ||
           kind == IssueKind::DuplicateBuilding;
}

std::string describeIssue(const CompiledGrammar& grammar, const ExpansionIssue& issue, uint64_t occurrences) {
    std::string text = issue.rule != kNullRule ? grammar.where(issue.rule) + ": " : grammar.name + ": ";
    text += issueIsError(issue.kind) ? "error: " : "warning: ";
    text += "building " + std::to_string(issue.building) + ": " + issueKindName(issue.kind);
    if (!issue.detail.empty()) text += " (" + issue.detail + ")";
    if (occurrences > 1) text += " [" + std::to_string(occurrences) + " times]";
    return text;
}

} // namespace hexlod::grammar
