#include "hexlod/grammar/terminal_set.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace hexlod::grammar {

namespace {
// glm::packSnorm4x16 rounds through libm's roundf, a call per component on the hottest
// path of expansion; adding +-0.5 and truncating rounds half away from zero the same way.
uint32_t snorm16(float v) {
    const float scaled = std::min(std::max(v, -1.0f), 1.0f) * 32767.0f;
    return static_cast<uint16_t>(static_cast<int16_t>(scaled + (scaled >= 0.0f ? 0.5f : -0.5f)));
}

// Float to half with round-to-nearest-even, after F. Giesen's float_to_half_fast3_rtne:
// bit arithmetic instead of glm::packHalf's branch per exponent range, which cost a tenth
// of expansion time. It matches glm except on exact ties, which it rounds to even as IEEE 754
// does (tests/grammar/terminal_record_test.cpp).
uint32_t half(float value) {
    uint32_t bits;
    std::memcpy(&bits, &value, sizeof(bits));
    const uint32_t sign = (bits >> 16) & 0x8000u;
    bits &= 0x7fffffffu;
    uint32_t out;
    if (bits >= 0x47800000u) { // 65536 and above: infinity, or NaN kept quiet
        out = bits > 0x7f800000u ? 0x7e00u : 0x7c00u;
    } else if (bits < 0x38800000u) { // below 2^-14: a subnormal half; let the FPU round it
        float magnitude;
        std::memcpy(&magnitude, &bits, sizeof(bits));
        const float shifted = magnitude + 0.5f;
        std::memcpy(&out, &shifted, sizeof(out));
        out -= 0x3f000000u;
    } else {
        const uint32_t odd = (bits >> 13) & 1u;
        bits += (static_cast<uint32_t>(15 - 127) << 23) + 0xfffu + odd;
        out = bits >> 13;
    }
    return sign | out;
}
} // namespace

TerminalRecord packTerminal(const glm::vec3& position, const glm::vec3& x, const glm::vec3& y,
                            const glm::vec3& z, const glm::vec2& size, float depthRatio, uint16_t shape,
                            uint32_t building) {
    glm::quat q = glm::quat_cast(glm::mat3(x, y, z));
    if (q.w < 0.0f) q = -q; // q and -q are the same rotation; one sign keeps the bytes unique
    TerminalRecord record;
    record.position[0] = position.x;
    record.position[1] = position.y;
    record.position[2] = position.z;
    record.building = building;
    record.orientation[0] = snorm16(q.x) | (snorm16(q.y) << 16);
    record.orientation[1] = snorm16(q.z) | (snorm16(q.w) << 16);
    record.size = half(size.x) | (half(size.y) << 16);
    record.shapeAndDepth = shape | (half(depthRatio) << 16);
    return record;
}

Terminal unpackTerminal(const TerminalRecord& record) {
    Terminal t;
    t.position = glm::vec3(record.position[0], record.position[1], record.position[2]);
    const glm::uint64 packed =
        glm::uint64(record.orientation[0]) | (glm::uint64(record.orientation[1]) << 32);
    const glm::vec4 q = glm::unpackSnorm4x16(packed);
    t.orientation = glm::normalize(glm::quat(q.w, q.x, q.y, q.z));
    t.size = glm::unpackHalf2x16(record.size);
    t.shape = static_cast<uint16_t>(record.shapeAndDepth & 0xffffu);
    t.depthRatio = glm::unpackHalf1x16(static_cast<glm::uint16>(record.shapeAndDepth >> 16));
    t.building = record.building;
    return t;
}

size_t TerminalSet::firstOfShape(uint16_t shape) const {
    size_t first = 0;
    for (uint16_t s = 0; s < shape && s < countPerShape.size(); ++s) first += countPerShape[s];
    return first;
}

} // namespace hexlod::grammar
