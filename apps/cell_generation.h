// `hexlod cells --generate`: expands every batch of a sample of cells into terminal sets
// and reports time and bytes per cell (docs/BENCHMARKS.md, "Per-cell generation").
#pragma once

#include "hexlod/cells/cell_index.h"
#include "hexlod/scene/scene_builder.h"

#include <nlohmann/json.hpp>

namespace hexlod::apps {

// Generates the cells at evenly spaced positions of index.cells(), at most `maxCells` of them
// (0: all). Returns per-cell time and bytes (in memory and encoded) as median, p95 and max.
nlohmann::json generateCells(const scene::BuiltScene& scene, const cells::CellIndex& index,
                             uint32_t maxCells);

} // namespace hexlod::apps
