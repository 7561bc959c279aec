// The compiled grammar: a flat rule map plus expression bytecode (thesis §4.3).
// Rules refer to each other by index, so expansion is a table walk with no name lookups.
#pragma once

#include "hexlod/grammar/bytecode.h"
#include "hexlod/grammar/diagnostics.h"

#include <cstdint>
#include <string>
#include <vector>

namespace hexlod::grammar {

enum class RuleOp : uint8_t {
    Extrude,
    Split,
    Repeat,
    Branch,
    Translate,
    Rotate,
    Cond,
    Shape,
    Explode,
    Project,
    Choose,
    Null
};
const char* ruleOpName(RuleOp op);

enum class Axis : uint8_t { X, Y, Z };
enum class RepeatMode : uint8_t { Fit, Equal };
enum class Pivot : uint8_t { Origin, Center };

constexpr uint32_t kNullRule = 0xffffffffu;
constexpr uint32_t kMaxSplitParts = 256; // also the most Choose alternatives

struct RuleArgumentRef {
    uint32_t expression = 0; // index into CompiledGrammar::expressions
    bool relative = false;   // `~size` in Split
};

struct CompiledRule {
    RuleOp op = RuleOp::Null;
    Axis axis = Axis::X;       // Split, Repeat, Rotate; Project's first axis
    Axis secondAxis = Axis::Y; // Project
    RepeatMode mode = RepeatMode::Fit;
    Pivot pivot = Pivot::Origin;
    bool extrudedStop = false;  // scopes entering this rule form the extruded set
    uint64_t key = 0;           // hash of the rule name: keys Choose and rand(), so adding or reordering
                                // other rules leaves every random pick alone
    uint16_t shape = 0;         // Shape
    uint32_t firstArgument = 0; // into CompiledGrammar::arguments
    uint32_t argumentCount = 0;
    uint32_t firstSuccessor = 0; // into CompiledGrammar::successors
    uint32_t successorCount = 0;
};

struct ParameterInfo {
    std::string name;
    float defaultValue = 0.0f;
    float minValue = 0.0f;
    float maxValue = 0.0f;
};

// A terminal shape as the grammar declares it; its mesh lives in render/.
struct ShapeInfo {
    std::string name;
    float width = 1.0f, height = 1.0f, depth = 0.0f; // nominal mesh bounds in metres
    float depthRatio = 0.0f;                         // default protrusion, see docs/grammar.md
    uint32_t triangles = 0;
};

struct CompiledGrammar {
    std::string name;
    std::vector<CompiledRule> rules;
    std::vector<std::string> ruleNames;
    std::vector<SourceLocation> ruleLocations;
    std::vector<RuleArgumentRef> arguments;
    std::vector<uint32_t> successors; // rule indices or kNullRule
    std::vector<Expression> expressions;
    std::vector<Instruction> code;
    std::vector<ParameterInfo> params;
    std::vector<ShapeInfo> shapes;
    uint32_t axiom = 0;
    uint64_t contentHash = 0; // hash of everything above except names and locations' columns

    int findParameter(const std::string& parameterName) const;
    int findShape(const std::string& shapeName) const;
    int findRule(const std::string& ruleName) const;
    std::vector<float> defaultParameters() const;
    std::string where(uint32_t rule) const; // "file:line:col rule 'Name'" for runtime diagnostics
};

// Parses and compiles a grammar. On any error the returned grammar is empty and
// `diagnostics` says why, with file:line:col.
CompiledGrammar compileGrammar(std::string_view source, const std::string& fileName,
                               DiagnosticList& diagnostics);

// Reads and compiles a grammar file; a missing or unreadable file is a diagnostic too.
CompiledGrammar compileGrammarFile(const std::string& path, DiagnosticList& diagnostics);

// Builds a building's parameter vector: the defaults with `overrides` applied. An unknown
// name, a NaN, an infinity or a value outside the declared range is an error naming the
// parameter, and the default stays in place.
struct ParameterOverride {
    std::string name;
    double value = 0.0;
};
std::vector<float> resolveParameters(const CompiledGrammar& grammar,
                                     const std::vector<ParameterOverride>& overrides,
                                     DiagnosticList& diagnostics);

} // namespace hexlod::grammar
