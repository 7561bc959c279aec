// Procedural meshes for every terminal shape the shipped grammars declare (windows, doors,
// mouldings, balconies, roofs, tower cladding, tree parts), built by small parametric
// generators in unit scope space (terminal_mesh.h).
#pragma once

#include "hexlod/grammar/compiled_grammar.h"
#include "hexlod/render/terminal_mesh.h"

#include <optional>
#include <string>
#include <vector>

namespace hexlod::render {

// Names of the shapes that have a generator, sorted.
std::vector<std::string> proceduralShapeNames();

// The mesh of a declared shape at its nominal size, at the generator's detail level whose
// triangle count is closest to `shape.triangles` (ties go to the coarser level). Empty when no
// generator has the shape's name.
std::optional<TerminalMesh> buildProceduralMesh(const grammar::ShapeInfo& shape);

// A coarser mesh of the same shape for where `fine` (the shape's mesh) is small on screen: the
// generator's level closest to its share of `fine`'s triangles (half, a fifth for the tree
// parts; tree_meshes.cpp says why), when it has at most
// three quarters of them. Empty when `fine` did not come from a generator (a glTF mesh, a
// fallback box) or no level is coarse enough.
std::optional<TerminalMesh> buildCoarserProceduralMesh(const grammar::ShapeInfo& shape,
                                                       const TerminalMesh& fine);

// A box filling the shape's bounds (u, v in [0, 1], t in [0, 1], or a flat quad for a shape of
// depth 0), magenta, for a shape with neither generator nor glTF mesh; `source` is "fallback".
TerminalMesh buildFallbackMesh(const grammar::ShapeInfo& shape);

} // namespace hexlod::render
