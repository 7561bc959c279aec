// Sizes of Split parts and Repeat tiles. Pure functions, so the rules' arithmetic,
// including degenerate sizes, is tested on its own (docs/grammar.md, "Split", "Repeat").
#pragma once

#include "hexlod/grammar/compiled_grammar.h"

#include <cstdint>

namespace hexlod::grammar {

enum class SubdivisionStatus : uint8_t { Ok, InvalidSize, TooManyTiles };

// Split: absolute parts keep their size and relative (~) parts share what remains in
// proportion to their weights. If the absolute parts overflow the scope they are scaled
// down to fit and relative parts get 0. Relative weights that sum to 0 get 0. A NaN,
// infinite or negative size counts as 0 and reports InvalidSize. `parts` receives `count`
// sizes that sum to at most `length`.
SubdivisionStatus splitSizes(float length, const float* sizes, const bool* relative, uint32_t count,
                             float* parts);

struct RepeatLayout {
    uint32_t tiles = 0;
    float tileSize = 0.0f;
    float margin = 0.0f; // before the first and after the last tile (fit mode)
};

// Repeat: `fit` places floor(length / size) tiles of exactly `size`, centred, with equal
// margins at both ends; `equal` places max(1, round(length / size)) tiles that fill the
// scope. A size that is not a positive finite number reports InvalidSize; more than
// `maxTiles` tiles report TooManyTiles. In both cases no tile is laid out.
SubdivisionStatus repeatLayout(float length, float size, RepeatMode mode, uint32_t maxTiles,
                               RepeatLayout& layout);

} // namespace hexlod::grammar
