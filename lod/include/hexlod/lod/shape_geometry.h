// A terminal mesh as the LOD4 pass draws it (ShapeTable): normals in unit scope space, and a
// double-sided surface (a leaf, a glass pane: each triangle emitted twice, once per side) as
// one triangle with the colour of either side, drawn without face culling. Before, the GL
// transformed both and culled one in its triangle setup, which bounds the LOD4 pass on
// llvmpipe; leaves are most of its triangles at street level.
#pragma once

#include "hexlod/render/terminal_mesh.h"

#include <cstdint>
#include <vector>

namespace hexlod::lod {

struct ShapeVertex {
    glm::vec3 position; // unit scope space, as stored
    glm::vec3 normal;   // unit scope space (render::unitSpaceNormal), of the front side
    uint32_t rgba;      // the front side's colour (MeshVertex::rgba)
    uint32_t backRgba;  // the back side's; the same as rgba in a one-sided mesh
};
static_assert(sizeof(ShapeVertex) == 32, "ShapeVertex is bound as a tightly packed 32-byte stride");

struct ShapeGeometry {
    std::vector<ShapeVertex> vertices;
    std::vector<uint32_t> indices;
    // Every triangle of the mesh had its reverse, and each pair became one triangle: draw it
    // without face culling. Else the mesh is as given, for drawing with back faces culled.
    bool twoSided = false;
};

// The mesh as ShapeGeometry. A mesh is two-sided only when each of its triangles pairs with
// another over the same three positions in reverse order, and each vertex normal of both is
// their face's (flat; the LOD4 vertex shader picks a side's colour from the vertex normal,
// which must then agree with the rasteriser's facing). Anything else keeps it one-sided.
ShapeGeometry shapeGeometry(const render::TerminalMesh& mesh);

} // namespace hexlod::lod
