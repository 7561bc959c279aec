// A contact sheet of an impostor: every view's albedo over a checkerboard (so coverage
// shows) beside its shape-space normals, tiles separated by grid lines.
#pragma once

#include "hexlod/impostor/impostor_atlas.h"

namespace hexlod::apps {

render::Image contactSheet(const impostor::ImpostorAtlas& atlas);

} // namespace hexlod::apps
