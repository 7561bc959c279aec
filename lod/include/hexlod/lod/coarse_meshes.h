// Which shapes get a coarser mesh for where they are small on screen: the tree grammars' parts.
// They have no impostor, so every tree within the billboard cut draws them at LOD4, and on the
// default street their leaves, 60 triangles each and a few pixels across, are about half of the
// LOD4 pass (docs/BENCHMARKS.md, "Where the LOD4 pass goes").
#pragma once

#include "hexlod/cells/batch_catalog.h"
#include "hexlod/lod/shape_table.h"
#include "hexlod/render/terminal_mesh_library.h"

#include <span>
#include <string>
#include <vector>

namespace hexlod::lod {

// One entry per tree shape whose procedural mesh has a coarser level (buildCoarserProceduralMesh),
// in global shape order (the ShapeTable's numbering of `meshes`). Shapes that share a mesh
// share its coarse mesh too.
std::vector<CoarseMesh> treeCoarseMeshes(const cells::BatchCatalog& catalog,
                                         const render::TerminalMeshLibrary& meshes);

// "coarse meshes: leaf 60 -> 28 triangles (deviation u 0.010, v 0.020, t 0.100), ..." for
// the reports, one entry per distinct coarse mesh; empty without any. `shapes` holds them.
std::string describeCoarseMeshes(std::span<const CoarseMesh> coarse, const ShapeTable& shapes);

} // namespace hexlod::lod
