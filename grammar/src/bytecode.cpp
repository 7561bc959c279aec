#include "hexlod/grammar/bytecode.h"

#include "hexlod/grammar/position_hash.h"

#include <cmath>
#include <cstring>

namespace hexlod::grammar {

namespace {
constexpr float kDegreesToRadians = 3.14159265358979323846f / 180.0f;
}

float evaluate(const Instruction* code, uint32_t count, const EvaluationInputs& inputs) {
    float stack[kMaxEvaluationStack];
    int top = -1;
    for (uint32_t pc = 0; pc < count; ++pc) {
        const Instruction& in = code[pc];
        switch (in.op) {
        case Opcode::PushConstant:
            stack[++top] = in.operand.value;
            break;
        case Opcode::LoadParam:
            stack[++top] = inputs.params[in.operand.index];
            break;
        case Opcode::LoadAccessor:
            stack[++top] = inputs.accessors[in.operand.index];
            break;
        case Opcode::Negate:
            stack[top] = -stack[top];
            break;
        case Opcode::Not:
            stack[top] = stack[top] != 0.0f ? 0.0f : 1.0f;
            break;
        case Opcode::Abs:
            stack[top] = std::fabs(stack[top]);
            break;
        case Opcode::Floor:
            stack[top] = std::floor(stack[top]);
            break;
        case Opcode::Ceil:
            stack[top] = std::ceil(stack[top]);
            break;
        case Opcode::Round:
            stack[top] = std::nearbyint(stack[top]);
            break;
        case Opcode::Sqrt:
            stack[top] = std::sqrt(stack[top]);
            break;
        case Opcode::Sin:
            stack[top] = std::sin(stack[top] * kDegreesToRadians);
            break;
        case Opcode::Cos:
            stack[top] = std::cos(stack[top] * kDegreesToRadians);
            break;
        case Opcode::BuildingRandom: {
            // Keyed by the stream number alone, so every rule reading the same stream sees the
            // same value for the whole building (a roof style, a colour scheme).
            const double stream = static_cast<double>(stack[top]);
            uint64_t bits;
            std::memcpy(&bits, &stream, sizeof(bits));
            stack[top] = unitFloat(combineKey(inputs.buildingKey, bits));
            break;
        }
        default: {
            // Binary and ternary operators consume their operands from the top of the stack.
            if (in.op == Opcode::Select || in.op == Opcode::Clamp) {
                const float c = stack[top--];
                const float b = stack[top--];
                float& a = stack[top];
                a = in.op == Opcode::Select ? (a != 0.0f ? b : c) : std::fmin(std::fmax(a, b), c);
                break;
            }
            const float b = stack[top--];
            float& a = stack[top];
            switch (in.op) {
            case Opcode::Add:
                a = a + b;
                break;
            case Opcode::Subtract:
                a = a - b;
                break;
            case Opcode::Multiply:
                a = a * b;
                break;
            case Opcode::Divide:
                a = a / b;
                break;
            case Opcode::Modulo:
                a = std::fmod(a, b);
                break;
            case Opcode::Less:
                a = a < b ? 1.0f : 0.0f;
                break;
            case Opcode::LessEqual:
                a = a <= b ? 1.0f : 0.0f;
                break;
            case Opcode::Greater:
                a = a > b ? 1.0f : 0.0f;
                break;
            case Opcode::GreaterEqual:
                a = a >= b ? 1.0f : 0.0f;
                break;
            case Opcode::Equal:
                a = a == b ? 1.0f : 0.0f;
                break;
            case Opcode::NotEqual:
                a = a != b ? 1.0f : 0.0f;
                break;
            case Opcode::And:
                a = (a != 0.0f && b != 0.0f) ? 1.0f : 0.0f;
                break;
            case Opcode::Or:
                a = (a != 0.0f || b != 0.0f) ? 1.0f : 0.0f;
                break;
            case Opcode::Min:
                a = std::fmin(a, b);
                break;
            case Opcode::Max:
                a = std::fmax(a, b);
                break;
            case Opcode::Pow:
                a = std::pow(a, b);
                break;
            case Opcode::Random: {
                const float u = unitFloat(combineKey(inputs.randomKey, pc));
                a = a + (b - a) * u;
                break;
            }
            default:
                break;
            }
        }
        }
    }
    return stack[0];
}

} // namespace hexlod::grammar
