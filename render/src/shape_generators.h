// The procedural shape generators, grouped by family in window_meshes.cpp, facade_meshes.cpp,
// tower_meshes.cpp, roof_meshes.cpp and tree_meshes.cpp. A generator builds its shape at a
// detail level (more glazing bars, slats, segments...); the library picks the level whose
// triangle count is closest to the grammar's `triangles` declaration.
#pragma once

#include "mesh_builder.h"

#include <span>

namespace hexlod::render {

struct ShapeGenerator {
    const char* name;
    int maxDetail; // levels 0..maxDetail
    void (*build)(MeshBuilder& builder, int detail);
    // The coarse level's share of the fine mesh's triangles (buildCoarserProceduralMesh).
    float coarseShare = 0.5f;
};

std::span<const ShapeGenerator> windowGenerators();
std::span<const ShapeGenerator> facadeGenerators();
std::span<const ShapeGenerator> towerGenerators();
std::span<const ShapeGenerator> roofGenerators();
std::span<const ShapeGenerator> treeGenerators();

// A small deterministic jitter in [0, 1) for placing repeated details (flowers, bark bumps).
float detailJitter(uint32_t a, uint32_t b);

} // namespace hexlod::render
