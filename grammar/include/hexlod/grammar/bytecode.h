// Expression bytecode: a tiny stack machine over floats (thesis §4.3 stores rule
// parameters as compiled expressions so that the expander never walks a tree).
#pragma once

#include <cstdint>
#include <vector>

namespace hexlod::grammar {

enum class Opcode : uint8_t {
    PushConstant, // operand.value
    LoadParam,    // operand.index into the building's parameter values
    LoadAccessor, // operand.index is an Accessor
    Negate,
    Not,
    Add,
    Subtract,
    Multiply,
    Divide,
    Modulo,
    Less,
    LessEqual,
    Greater,
    GreaterEqual,
    Equal,
    NotEqual,
    And,
    Or,
    Select, // c ? a : b with c, a, b on the stack
    Min,
    Max,
    Abs,
    Floor,
    Ceil,
    Round,
    Sqrt,
    Sin, // degrees, like Rotate
    Cos, // degrees
    Pow,
    Clamp,
    Random,         // rand(lo, hi), keyed by scope position and call site
    BuildingRandom, // building_rand(stream): one value per building and stream
};

// Scope accessors readable from expressions; see docs/grammar.md for their meaning.
enum class Accessor : uint8_t {
    Width,
    Height,
    SizeZ,
    Elevation,
    Floor,
    Floors,
    Index,
    Count,
    Level,
    Depth,
    NormalX,
    NormalY,
    NormalZ,
    WorldNormalX,
    WorldNormalY,
    WorldNormalZ,
    Atom,
    Atoms,
    Building,
    Count_,
};
constexpr int kAccessorCount = static_cast<int>(Accessor::Count_);

struct Instruction {
    Opcode op;
    union {
        float value;
        uint32_t index;
    } operand;
};
static_assert(sizeof(Instruction) == 8);

struct Expression {
    uint32_t first = 0; // offset of its first instruction in CompiledGrammar::code
    uint32_t count = 0;
    bool isBoolean = false;
    bool isConstant = false; // folded at compile time into constantValue
    float constantValue = 0.0f;
};

constexpr int kMaxEvaluationStack = 32;

struct EvaluationInputs {
    const float* params = nullptr;
    const float* accessors = nullptr; // kAccessorCount values for the current scope
    uint64_t randomKey = 0;           // position key of the scope; rand() mixes in its call site
    uint64_t buildingKey = 0;         // seed and building only, for building_rand()
};

// Runs `count` instructions starting at `code`. The compiler guarantees a stack depth of at
// most kMaxEvaluationStack and that the program leaves exactly one value.
float evaluate(const Instruction* code, uint32_t count, const EvaluationInputs& inputs);

} // namespace hexlod::grammar
