// One shape's baked views (ARCHITECTURE.md §4, "Impostors"): albedo with coverage, and the
// shape-space normal with depth, each view a tile of the layout's atlas.
#pragma once

#include "hexlod/impostor/view_layout.h"
#include "hexlod/render/image.h"

#include <cstdint>
#include <string>

namespace hexlod::impostor {

struct ImpostorAtlas {
    std::string shape; // a terminal shape's name, or "tree:<species>"
    ViewLayout layout;
    uint64_t contentKey = 0;                    // bakeKey() of what was baked: the store's address
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f}; // shape space, metres
    glm::vec3 centre{0.0f};                     // of the bounding sphere every view is fitted to
    float radius = 1.0f;
    render::Image albedo;      // RGBA, atlasSize^2; alpha 0 where the shape is absent
    render::Image normalDepth; // xyz: shape-space normal; w: depth toward the viewer / radius, -1 empty

    // GPU bytes: two RGBA16F textures.
    uint64_t byteSize() const { return uint64_t(albedo.width) * albedo.height * 16; }
};

// The content address of a bake: the geometry's hash, its nominal size, the layout and the
// store's format version. Equal keys mean the same views.
uint64_t bakeKey(uint64_t geometryHash, const glm::vec3& nominalSize, const ViewLayout& layout);

} // namespace hexlod::impostor
