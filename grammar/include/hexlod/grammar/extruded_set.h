// The extruded set: what LOD0 and LOD1 draw instead of terminals (thesis §7.3). Per
// building it keeps the base volume and the scopes where expansion was cut off (the
// facades), with the parameters LOD1's per-pixel grammar interpreter needs.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace hexlod::grammar {

// A scope that entered an extruded-set stop rule: usually a facade face or a roof edge.
struct ExtrudedElement {
    glm::vec3 origin{0.0f}; // cell-local
    glm::vec3 axisX{1, 0, 0};
    glm::vec3 axisY{0, 0, 1};
    glm::vec2 size{0.0f};
    uint32_t rule = 0; // the stop rule, where LOD1 resumes the grammar
    uint32_t atom = 0; // footprint edge it came from
    // The derivation state LOD1 needs to resume exactly where expansion went on: the scope's
    // position key (its random picks) and the accessors expressions read.
    uint64_t key = 0;
    int32_t floor = 0, floors = 1, index = 0, count = 1;
    uint16_t level = 0, depth = 0;
};

struct ExtrudedBuilding {
    uint32_t building = 0;
    uint32_t firstVertex = 0, vertexCount = 0;   // cleaned CCW footprint in ExtrudedSet::footprints
    uint32_t firstElement = 0, elementCount = 0; // in ExtrudedSet::elements
    uint32_t firstParameter = 0;                 // grammar.params.size() values in ExtrudedSet::parameters
    float baseElevation = 0.0f;                  // cell-local
    float height = 0.0f;                         // top of the base volume above baseElevation
    uint16_t wallMaterial = 0;                   // LOD0 wall texture
};

struct ExtrudedSet {
    std::vector<ExtrudedBuilding> buildings;
    std::vector<glm::vec2> footprints; // cell-local x, y
    std::vector<ExtrudedElement> elements;
    std::vector<float> parameters;

    size_t byteSize() const {
        return buildings.size() * sizeof(ExtrudedBuilding) + footprints.size() * sizeof(glm::vec2) +
               elements.size() * sizeof(ExtrudedElement) + parameters.size() * sizeof(float);
    }
};

} // namespace hexlod::grammar
