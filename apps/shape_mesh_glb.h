// One terminal shape's mesh as a self-contained .glb, for clients that draw terminals
// themselves (the web viewer, GET /api/v1/meshes/...): the mesh in unit scope space
// (render/terminal_mesh.h), so a client places it on a terminal record with T·R·S, S = (w, h,
// depthRatio·min(w, h)), exactly as the renderer does. NORMAL holds the unit-space mesh's
// normals, which that scale's inverse transpose carries to the world (glTF's node-scale rule).
// No node transform, no z-up turn: record space is what the client works in.
#pragma once

#include "hexlod/render/terminal_mesh.h"

#include <cstdint>
#include <string>
#include <vector>

namespace hexlod::apps {

// `name` becomes the mesh's name; asset.extras.hexlod records the nominal size and the content
// hash.
std::vector<uint8_t> shapeMeshGlb(const render::TerminalMesh& mesh, const std::string& name);

} // namespace hexlod::apps
