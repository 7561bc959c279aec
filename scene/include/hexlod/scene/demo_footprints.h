// Procedural demo footprints for `hexlod expand --demo N`: mixed shapes and sizes on a
// grid of lots, every choice keyed by (seed, building id) so any subset regenerates alike.
#pragma once

#include "hexlod/grammar/compiled_grammar.h"
#include "hexlod/grammar/expander.h"

#include <cstdint>
#include <vector>

namespace hexlod::scene {

enum class DemoShape : uint8_t { Rectangle, RotatedRectangle, LShape, UShape, TShape, Polygon, count_ };

struct DemoOptions {
    uint32_t count = 1000;
    uint64_t seed = 1;
    double lotSpacing = 60.0; // metres between lot centres
};

// Building ids are 0..count-1. Parameters are left empty (grammar defaults); see
// demoParameterOverrides for per-building variation.
std::vector<grammar::BuildingInput> makeDemoFootprints(const DemoOptions& options);

DemoShape demoShapeOf(uint64_t seed, uint32_t building);

// Varies the height of each building: if the grammar declares `floors`, it is drawn from
// [default / 2, default * 1.5] clipped to the declared range, keyed by seed and building.
std::vector<grammar::ParameterOverride> demoParameterOverrides(const grammar::CompiledGrammar& grammar,
                                                               uint64_t seed, uint32_t building);

} // namespace hexlod::scene
