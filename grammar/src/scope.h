// The unit of work of the expander (as ShapeML's Scope { transform, size }): an oriented
// box in cell-local metres plus the derivation state that expressions can read.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>

namespace hexlod::grammar {

struct Scope {
    glm::vec3 origin{0.0f}; // corner at local (0, 0, 0)
    glm::vec3 x{1, 0, 0};   // along the facade
    glm::vec3 y{0, 0, 1};   // up the facade
    glm::vec3 z{0, -1, 0};  // out of the facade
    glm::vec3 size{0.0f};
    uint64_t key = 0; // position key: seed, building, atom and the successor slots taken
    int32_t floor = 0, floors = 1;
    int32_t index = 0, count = 1;
    uint16_t level = 0;    // Branch applications on the path
    uint16_t depth = 0;    // rule applications on the path
    uint8_t dimension = 1; // 1 atom (segment), 2 face, 3 volume

    glm::vec3 axis(int a) const { return a == 0 ? x : (a == 1 ? y : z); }
    glm::vec3 center() const {
        return origin + x * (0.5f * size.x) + y * (0.5f * size.y) + z * (0.5f * size.z);
    }
};

} // namespace hexlod::grammar
