// The procedural city (the embedded default scene): a road network, then blocks, then lots,
// then footprints, with districts that use different grammars, per-building heights and
// parameters, and trees along streets and in parks. Every choice is keyed by position
// (seed and coordinates), so any part of the city regenerates identically.
#pragma once

#include "hexlod/grammar/expander.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace hexlod::scene {

// A district type: which grammar its buildings use and how tall they grow.
struct DistrictSpec {
    std::string grammar;    // grammar name in the scene config
    double share = 1.0;     // relative share of the city's area
    double minFloors = 2.0; // the `floors` parameter is drawn in [minFloors, maxFloors]
    double maxFloors = 6.0;
    double lotWidth = 20.0; // typical lot frontage, metres
    double lotDepth = 25.0; // typical lot depth, metres
};

struct CityOptions {
    uint64_t seed = 1;
    uint32_t buildings = 10000; // exactly this many footprints are generated
    uint32_t trees = 0;         // exactly this many trees (0: none)
    uint32_t species = 7;       // trees are spread over species 0..species-1
    double blockSize = 120.0;   // mean distance between streets, metres
    double streetWidth = 14.0;
    double parkShare = 0.06;             // share of blocks kept as parks (trees, no buildings)
    std::vector<DistrictSpec> districts; // ordered from the centre outwards; must not be empty
};

struct GeneratedBuilding {
    grammar::BuildingInput input; // id, footprint in world metres, base elevation 0
    uint32_t district = 0;        // index into CityOptions::districts
    double floors = 0.0;          // drawn per building; the scene maps it to the grammar's `floors`
};

struct TreeInstance {
    glm::dvec2 position{0.0};
    uint32_t species = 0;
    float scale = 1.0f;
    bool inPark = false; // otherwise along a street
};

struct RoadSegment {
    glm::dvec2 a{0.0}, b{0.0};
    double width = 0.0;
};

struct GeneratedCity {
    std::vector<GeneratedBuilding> buildings; // ids 0..n-1
    std::vector<TreeInstance> trees;
    std::vector<RoadSegment> roads;
    std::vector<std::vector<glm::dvec2>> parks;
    glm::dvec2 extentMin{0.0}, extentMax{0.0};
};

// Throws std::invalid_argument naming the option when options are unusable (no districts,
// non-positive sizes, NaN).
GeneratedCity generateCity(const CityOptions& options);

} // namespace hexlod::scene
