#include "hexlod/grammar/terminal_set.h"

#include <glm/gtc/packing.hpp>

namespace hexlod::grammar {

TerminalRecord packTerminal(const glm::vec3& position, const glm::vec3& x, const glm::vec3& y,
                            const glm::vec3& z, const glm::vec2& size, float depthRatio, uint16_t shape,
                            uint32_t building) {
    glm::quat q = glm::quat_cast(glm::mat3(x, y, z));
    if (q.w < 0.0f) q = -q; // q and -q are the same rotation; one sign keeps the bytes unique
    const glm::uint64 packed = glm::packSnorm4x16(glm::vec4(q.x, q.y, q.z, q.w));
    TerminalRecord record;
    record.position[0] = position.x;
    record.position[1] = position.y;
    record.position[2] = position.z;
    record.building = building;
    record.orientation[0] = static_cast<uint32_t>(packed);
    record.orientation[1] = static_cast<uint32_t>(packed >> 32);
    record.size = glm::packHalf2x16(size);
    record.shapeAndDepth = shape | (static_cast<uint32_t>(glm::packHalf1x16(depthRatio)) << 16);
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
