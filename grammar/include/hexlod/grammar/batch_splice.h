// Splicing an edited batch: an edit usually changes a few buildings of a batch, and expanding
// the whole batch again repeats every other building's work (one tower of a business batch
// of a hundred). These put a fresh expansion of just the changed buildings where a whole
// expansion would put them, byte for byte: expandBatch's order is by shape, then building
// id, then derivation, and a building's output does not depend on the others of its batch.
#pragma once

#include "hexlod/grammar/extruded_set.h"
#include "hexlod/grammar/terminal_set.h"

#include <span>

namespace hexlod::grammar {

// `base` and `replacement` as expandBatch leaves them, of the same grammar: `replacement`
// expanded from the changed buildings alone. `replaced` holds their ids, ascending; the
// records of those ids in `base` give way to `replacement`'s. The header is `base`'s (the
// caller sets the new key).
TerminalSet spliceTerminals(const TerminalSet& base, const TerminalSet& replacement,
                            std::span<const uint32_t> replaced);

// The same for the extruded sets: buildings in id order, their footprints, elements and
// parameters moved with them.
ExtrudedSet spliceExtruded(const ExtrudedSet& base, const ExtrudedSet& replacement,
                           std::span<const uint32_t> replaced);

} // namespace hexlod::grammar
