// Footprint clean-up: turns a raw polygon into the 1D atoms of segment-based expansion
// (thesis §4.4.2). The clean-up is documented in docs/grammar.md ("Footprints").
#pragma once

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace hexlod::grammar {

struct CleanFootprint {
    std::vector<glm::dvec2> points; // counter-clockwise, no repeated or collinear points
    double area = 0.0;              // positive
    bool reversed = false;          // the input was clockwise
    bool selfIntersecting = false;  // kept and expanded, but reported
    size_t removedPoints = 0;       // duplicates, closing point, collinear points and spikes
};

// Returns false with `error` set when nothing usable remains: fewer than 3 distinct
// points, zero area, or non-finite coordinates.
bool cleanFootprint(const std::vector<glm::dvec2>& raw, CleanFootprint& out, std::string& error);

// Whether any two non-adjacent edges cross or touch. O(n^2), which is fine for building
// footprints (10,000 vertices take well under a second).
bool isSelfIntersecting(const std::vector<glm::dvec2>& polygon);

} // namespace hexlod::grammar
