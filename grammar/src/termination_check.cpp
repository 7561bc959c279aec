#include "termination_check.h"

#include <algorithm>

namespace hexlod::grammar {
namespace {

// Cond and Choose pick one successor, so one ending alternative suffices; every other
// rule hands scopes to all of its successors, so all of them must be able to end.
bool needsAllSuccessors(RuleOp op) {
    return op != RuleOp::Cond && op != RuleOp::Choose;
}

std::vector<bool> terminatingRules(const CompiledGrammar& grammar) {
    const size_t n = grammar.rules.size();
    std::vector<bool> terminates(n, false);
    for (bool changed = true; changed;) {
        changed = false;
        for (size_t r = 0; r < n; ++r) {
            if (terminates[r]) continue;
            const CompiledRule& rule = grammar.rules[r];
            const bool all = needsAllSuccessors(rule.op);
            // A Cond without an else drops the scope when false: an implicit NULL that ends.
            bool result = all || (rule.op == RuleOp::Cond && rule.successorCount == 1);
            for (uint32_t s = 0; s < rule.successorCount; ++s) {
                const uint32_t successor = grammar.successors[rule.firstSuccessor + s];
                const bool ends = successor == kNullRule || terminates[successor];
                result = all ? (result && ends) : (result || ends);
            }
            if (result) {
                terminates[r] = true;
                changed = true;
            }
        }
    }
    return terminates;
}

// Follows non-terminating successors from `start` until a rule repeats; returns the cycle.
std::vector<uint32_t> findCycle(const CompiledGrammar& grammar, const std::vector<bool>& terminates,
                                uint32_t start) {
    std::vector<uint32_t> path{start};
    uint32_t current = start;
    while (true) {
        const CompiledRule& rule = grammar.rules[current];
        uint32_t next = kNullRule;
        for (uint32_t s = 0; s < rule.successorCount && next == kNullRule; ++s) {
            const uint32_t successor = grammar.successors[rule.firstSuccessor + s];
            if (successor != kNullRule && !terminates[successor]) next = successor;
        }
        if (next == kNullRule) return path;
        // An index, not an iterator: push_back may reallocate the path.
        const size_t seen = static_cast<size_t>(std::find(path.begin(), path.end(), next) - path.begin());
        path.push_back(next);
        if (seen + 1 < path.size()) return {path.begin() + static_cast<std::ptrdiff_t>(seen), path.end()};
        current = next;
    }
}

} // namespace

void checkTermination(const CompiledGrammar& grammar, DiagnosticList& diagnostics) {
    const std::vector<bool> terminates = terminatingRules(grammar);
    std::vector<bool> reported(grammar.rules.size(), false);
    for (uint32_t r = 0; r < grammar.rules.size(); ++r) {
        if (terminates[r] || reported[r]) continue;
        const std::vector<uint32_t> cycle = findCycle(grammar, terminates, r);
        reported[r] = true;
        // A rule that only leads into a cycle already reported is its victim, not a new error.
        if (std::all_of(cycle.begin(), cycle.end(),
                        [&](uint32_t rule) { return reported[rule] && rule != r; })) {
            continue;
        }
        std::string chain;
        for (const uint32_t rule : cycle) {
            chain += (chain.empty() ? "" : " -> ") + grammar.ruleNames[rule];
            reported[rule] = true;
        }
        const uint32_t head = cycle.front();
        diagnostics.error(grammar.ruleLocations[head],
                          "unbounded recursion: rule '" + grammar.ruleNames[head] + "' can never end (" +
                              chain +
                              "); recursion must pass through Cond or Choose with an alternative that ends");
    }
}

} // namespace hexlod::grammar
