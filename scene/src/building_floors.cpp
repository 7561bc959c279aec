#include "hexlod/scene/building_floors.h"

#include <algorithm>
#include <cmath>

namespace hexlod::scene {

double floorsFromImport(const grammar::CompiledGrammar& g, double height, double levels) {
    if (std::isfinite(levels)) return levels;
    const int floorHeight = g.findParameter("floor_h");
    if (!std::isfinite(height) || floorHeight < 0) return NAN;
    return height / g.params[floorHeight].defaultValue;
}

void appendFloors(const grammar::CompiledGrammar& g, double floors,
                  std::vector<grammar::ParameterOverride>& list) {
    const int index = g.findParameter("floors");
    if (index < 0 || !std::isfinite(floors)) return;
    const grammar::ParameterInfo& info = g.params[index];
    list.push_back({"floors", std::clamp(std::round(floors), double(info.minValue), double(info.maxValue))});
}

} // namespace hexlod::scene
