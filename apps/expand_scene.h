// `hexlod expand --scene S`: builds a scene from its config and expands every grammar batch,
// buildings and trees, reporting each batch and the totals.
#pragma once

#include "expand_command.h"

namespace hexlod::apps {

int runSceneExpansion(const ExpandOptions& options);

} // namespace hexlod::apps
