// Reachability over the flat rule map: a depth-first walk of successor indices.
#include "hexlod/grammar/rule_reachability.h"

namespace hexlod::grammar {

std::vector<bool> reachableRules(const CompiledGrammar& grammar) {
    std::vector<bool> reached(grammar.rules.size(), false);
    if (grammar.rules.empty()) return reached;
    std::vector<uint32_t> stack{grammar.axiom};
    reached[grammar.axiom] = true;
    while (!stack.empty()) {
        const CompiledRule& rule = grammar.rules[stack.back()];
        stack.pop_back();
        for (uint32_t s = 0; s < rule.successorCount; ++s) {
            const uint32_t successor = grammar.successors[rule.firstSuccessor + s];
            if (successor != kNullRule && !reached[successor]) {
                reached[successor] = true;
                stack.push_back(successor);
            }
        }
    }
    return reached;
}

std::vector<bool> emittedShapes(const CompiledGrammar& grammar) {
    std::vector<bool> emitted(grammar.shapes.size(), false);
    std::vector<bool> reached = reachableRules(grammar);
    for (size_t r = 0; r < grammar.rules.size(); ++r) {
        if (reached[r] && grammar.rules[r].op == RuleOp::Shape) emitted[grammar.rules[r].shape] = true;
    }
    return emitted;
}

} // namespace hexlod::grammar
