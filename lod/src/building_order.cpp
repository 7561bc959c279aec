#include "hexlod/lod/building_order.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <utility>

namespace hexlod::lod {

std::vector<glm::uvec2> nearestFirstRuns(const std::vector<render::VolumeBuilding>& buildings,
                                         const std::vector<uint32_t>& kept, const glm::vec3& origin) {
    std::vector<std::pair<float, uint32_t>> order;
    order.reserve(kept.size());
    for (const uint32_t b : kept) {
        // The camera is the origin: per axis, how far the box lies beyond it (0 within).
        const glm::vec3 lo = origin + buildings[b].boundsMin, hi = origin + buildings[b].boundsMax;
        const glm::vec3 gap = glm::max(glm::max(lo, -hi), glm::vec3(0.0f));
        order.emplace_back(glm::dot(gap, gap), b);
    }
    std::stable_sort(order.begin(), order.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<glm::uvec2> runs;
    for (const auto& [distance, b] : order) appendRun(runs, buildings[b].firstIndex, buildings[b].indexCount);
    return runs;
}

std::vector<glm::uvec2> buildingRuns(const std::vector<render::VolumeBuilding>& buildings,
                                     const std::vector<uint32_t>& kept) {
    std::vector<glm::uvec2> runs;
    for (const uint32_t b : kept) appendRun(runs, buildings[b].firstIndex, buildings[b].indexCount);
    return runs;
}

void appendRun(std::vector<glm::uvec2>& runs, uint32_t first, uint32_t count) {
    if (!runs.empty() && runs.back().x + runs.back().y == first)
        runs.back().y += count;
    else
        runs.emplace_back(first, count);
}

} // namespace hexlod::lod
