#include "hexlod/lod/lod1_elements.h"
#include "hexlod/grammar/position_hash.h"

namespace hexlod::lod {

std::vector<GpuLod1Element> packLod1Elements(const grammar::ExtrudedSet& set, uint64_t seed) {
    std::vector<GpuLod1Element> out(set.elements.size());
    for (const grammar::ExtrudedBuilding& building : set.buildings) {
        // The expander's building key, for building_rand().
        const uint64_t buildingKey =
            grammar::combineKey(grammar::combineKey(seed, building.building), 0xb01d1e5ull);
        for (uint32_t i = 0; i < building.elementCount; ++i) {
            const grammar::ExtrudedElement& e = set.elements[building.firstElement + i];
            GpuLod1Element& g = out[building.firstElement + i];
            g.origin = glm::vec4(e.origin, building.baseElevation);
            g.axisX = glm::vec4(e.axisX, e.size.x);
            g.axisY = glm::vec4(e.axisY, e.size.y);
            g.rule = glm::uvec4(e.rule, building.firstParameter, uint32_t(buildingKey),
                                uint32_t(buildingKey >> 32));
            g.state = glm::ivec4(e.floor, e.floors, e.index, e.count);
            g.state2 = glm::uvec4(e.level, e.depth, e.atom, building.vertexCount);
            g.state3 = glm::uvec4(building.building, uint32_t(e.key), uint32_t(e.key >> 32), 0u);
        }
    }
    return out;
}

} // namespace hexlod::lod
