// User terminal shapes from glTF 2.0 files (.glb or .gltf), through tinygltf: the scene
// config's `shapes` list maps a shape name to a file (docs/scene.md).
//
// What is read: the default scene's node hierarchy (or every root node, or every mesh when the
// file has no nodes) flattened with the node transforms; every TRIANGLES primitive, indexed or
// not; POSITION, NORMAL (computed per face when missing), TEXCOORD_0 and COLOR_0 (float,
// normalised unsigned byte or short, vec3 or vec4), multiplied by the material's
// baseColorFactor. A baseColorTexture is sampled per vertex at its TEXCOORD_0 (nearest texel,
// repeat wrap, sRGB decoded), which keeps the colours of palette-textured models; without
// texture coordinates the texture's mean colour is used. Other primitive modes, morph targets
// and skins are skipped and said so in `warnings`.
//
// Fitting: glTF +X becomes scope x (along the facade), +Y scope y (up), +Z out of the facade.
// The model's bounds are stretched so that x and y span [0, 1] and z spans t in [0, 1] (its
// back at the wall plane, its front at full protrusion); a model that is flat in z lies at
// t = 0. Normals are stored for the shape at its nominal size (terminal_mesh.h); a shape of
// nominal depth 0 keeps the model's own depth-to-width proportion for them.
//
// Errors name the file: missing or unreadable, not glTF, a required extension that is not
// supported (Draco, meshopt), no triangles, non-finite or out-of-range data, bounds that are
// degenerate in x or y or larger than 1e6 m, more than kMaxGltfTriangles triangles.
#pragma once

#include "hexlod/render/terminal_mesh.h"

#include <string>
#include <vector>

namespace hexlod::render {

inline constexpr size_t kMaxGltfTriangles = size_t(1) << 22;
inline constexpr double kMaxGltfExtent = 1e6; // metres, on any axis

struct GltfLoadResult {
    bool ok = false;
    TerminalMesh mesh;                 // source = the path
    std::string error;                 // "<path>: <what is wrong>" when !ok
    std::vector<std::string> warnings; // skipped primitives and the like, each naming the file
};

// `shape` names the mesh; `nominalSize` is nominalShapeSize() of the shape's declaration.
GltfLoadResult loadGltfMesh(const std::string& path, const std::string& shape, const glm::vec3& nominalSize);

} // namespace hexlod::render
