// Internal to the city generator: splitting one block into lots along its streets and
// drawing a footprint inside each lot. Blocks are axis-aligned rectangles already inset
// from the street centrelines, so lots and footprints never reach a road.
#pragma once

#include "hexlod/grammar/position_hash.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace hexlod::scene::detail {

// Position-keyed uniform draws: draw k under `key`, never a shared generator state.
struct Draws {
    uint64_t key;
    uint32_t next = 0;
    double uniform(double lo, double hi) {
        return lo + (hi - lo) * grammar::unitFloat(grammar::combineKey(key, next++));
    }
};

struct Rect {
    glm::dvec2 lo{0.0}, hi{0.0};
    glm::dvec2 size() const { return hi - lo; }
};

// The street a lot faces; its footprint's front and openings are oriented towards it.
enum class Side : uint8_t { South, East, North, West };

struct Lot {
    Rect rect;
    Side front = Side::South;
};

// Appends the lots of `block`: strips of about `lotDepth` along each street, cut into
// frontages of about `lotWidth`, with corner lots where the strips meet and the inner
// courtyard left empty. Lots tile part of the block without overlapping.
void subdivideBlock(const Rect& block, double lotWidth, double lotDepth, uint64_t blockKey,
                    std::vector<Lot>& out);

// A counter-clockwise footprint strictly inside `lot`: mostly rectangles, with L, U and T
// shapes, chamfered, rotated and polygonal ones mixed in.
std::vector<glm::dvec2> makeFootprint(const Lot& lot, uint64_t lotKey);

} // namespace hexlod::scene::detail
