// Where an impostor's views look from and where they sit in its atlas (thesis §7.3.1;
// octahedral impostors after Brucks' "Octahedral Impostors", 2018).
//
// Facade terminals are seen only from in front of their wall, so their views cover the
// hemisphere z >= 0 of shape space, on a hemi-octahedral grid: the grid's vertices, rim
// included, so the views reach grazing angles. Trees are seen from everywhere, so their views
// cover the sphere on a full octahedral grid, one view at each cell centre (the octahedral
// map doubles points on its border; cell centres never land there). Both maps are bijections
// between the unit square and their part of the sphere, so no two views share a direction.
//
// Every view is an orthographic image of the shape's bounding sphere, the same scale for
// all views, so the views of a shape can be blended pixel for pixel. A view is a square tile
// of `viewResolution` texels, of which `padding` on each side stay empty (alpha 0) so
// bilinear filtering near a tile's edge never reads the next view.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>

namespace hexlod::impostor {

enum class ViewSphere : uint8_t { Hemisphere, FullSphere };

inline constexpr uint32_t kMinGrid = 2, kMaxGrid = 32, kDefaultGrid = 8;
// The widest atlas a layout may make, and the widest view, in texels per side.
inline constexpr uint32_t kMaxAtlasSize = 16384, kMaxViewResolution = 1024;

struct ViewLayout {
    ViewSphere sphere = ViewSphere::Hemisphere;
    uint32_t grid = kDefaultGrid;  // N: N x N views
    uint32_t viewResolution = 128; // texels per tile side
    uint32_t padding = 2;          // empty texels on each side of a tile

    uint32_t viewCount() const { return grid * grid; }
    uint32_t atlasSize() const { return grid * viewResolution; } // the atlas is square
    // The part of a tile the view's sphere projects into, in texels.
    uint32_t innerResolution() const { return viewResolution - 2 * padding; }

    // Direction from the shape's centre toward the viewer of view `index` (row-major, index =
    // row * grid + column), unit length, in shape space (+z out of the wall).
    glm::vec3 direction(uint32_t index) const;
    // Texel origin (column, row) of a view's tile in the atlas, rows from the top.
    glm::uvec2 tileOrigin(uint32_t index) const;

    // False with a reason for a grid outside [2, 32], a resolution that leaves no inner area
    // or an atlas larger than 16384 texels.
    bool validate(std::string& error) const;
};

// The frame a view looks along: `forward` points from the shape toward the viewer, `right` and
// `up` span the image (up is the top of the tile). Up follows shape +y for facades (up the
// wall) and +z for trees (the sky), or the other axis where the view looks along it. Baking,
// the CPU reconstruction and the GLSL one (impostor_views.glsl) all use this frame.
struct ViewBasis {
    glm::vec3 right, up, forward;
};
ViewBasis viewBasis(ViewSphere sphere, const glm::vec3& forward);

// Octahedral encodings: unit direction <-> point of [-1, 1]^2.
glm::vec2 encodeOctahedral(const glm::vec3& direction);
glm::vec3 decodeOctahedral(const glm::vec2& point);
// Hemi-octahedral, for z >= 0: the octahedral map of the upper half turned by 45 degrees so
// it fills the square.
glm::vec2 encodeHemiOctahedral(const glm::vec3& direction);
glm::vec3 decodeHemiOctahedral(const glm::vec2& point);

} // namespace hexlod::impostor
