// Which shapes get a coarser mesh for where they are small on screen at LOD4: every shape whose
// generator has a level with at most three quarters of its triangles. The LOD4 pass is bound by
// llvmpipe's triangle setup (docs/BENCHMARKS.md, "Where the LOD4 pass goes"): tree parts draw
// at LOD4 out to the billboard cut, and facade parts out to LOD3's distance, a few pixels across
// by then.
#pragma once

#include "hexlod/cells/batch_catalog.h"
#include "hexlod/lod/shape_table.h"
#include "hexlod/render/terminal_mesh_library.h"

#include <span>
#include <string>
#include <vector>

namespace hexlod::lod {

// One entry per shape whose procedural mesh has a coarser level (buildCoarserProceduralMesh)
// within a finite deviation (meshDeviation: one that keeps every colour and shading of the
// mesh), in global shape order (the ShapeTable's numbering of `meshes`). Shapes that share a
// mesh share its coarse mesh too.
std::vector<CoarseMesh> coarseMeshes(const cells::BatchCatalog& catalog,
                                     const render::TerminalMeshLibrary& meshes);

// "coarse meshes: leaf 60 -> 28 triangles (deviation u 0.010, v 0.020, t 0.100), ..." for
// the reports, one entry per distinct coarse mesh; empty without any. `shapes` holds them.
std::string describeCoarseMeshes(std::span<const CoarseMesh> coarse, const ShapeTable& shapes);

} // namespace hexlod::lod
