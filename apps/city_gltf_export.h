// `hexlod export` for glTF: the full detail (LOD4) of chosen cells as one glTF 2.0 file
// (thesis §7.6). Each terminal mesh appears once; its terminals are instances through
// EXT_mesh_gpu_instancing (per instance TRANSLATION, ROTATION and SCALE: a terminal's scope is
// exactly T·R·S of the unit-scope-space mesh, with S = (w, h, depthRatio·min(w, h))), or, with
// `flatten`, baked into plain triangles for renderers without the extension. The buildings'
// base volumes (the extruded set) close the roofs.
//
// Node layout, for precision far from the origin: a root node turns hexlod's z-up world into
// glTF's y-up; under it one node per cell, translated by the cell origin minus the reference
// origin (the first chosen cell's origin, computed in double), whose children hold the
// cell-relative instances and base volumes. The reference origin is in the asset's
// extras.hexlod.origin, so world position = origin + node chain.
//
// Streaming: cells are expanded one at a time and their bytes appended to the binary buffer at
// once (gltf_binary_stream.h); only the JSON and one cell's data are ever held in memory.
#pragma once

#include "hexlod/cells/batch_catalog.h"
#include "hexlod/render/terminal_mesh_library.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace hexlod::apps {

struct CityExportOptions {
    std::string output;                 // .glb, or .gltf (with a .bin beside it)
    std::vector<cells::HexCoord> cells; // empty: every occupied cell
    bool flatten = false;
    uint64_t maxBytes = 0;        // refuse to write a buffer past this; 0: the format's limit
    float baseVolumeInset = 0.5f; // metres, so recessed glass stays in front of the shell
};

struct CityExportReport {
    bool ok = false;
    std::string error;
    uint64_t bytes = 0; // of the written file(s)
    uint32_t cells = 0, batches = 0;
    uint64_t terminals = 0, instances = 0; // instances: as instancing entries, or baked (flatten)
    uint64_t triangles = 0;                // world-space triangles: instances × mesh + base volumes
    uint64_t baseVolumeTriangles = 0;
    uint32_t gltfMeshes = 0, terminalMeshes = 0;      // glTF meshes written; distinct terminal meshes used
    glm::dvec3 origin{0.0};                           // the reference origin
    std::map<std::string, uint64_t> instancesPerMesh; // "grammar/shape"
    std::vector<std::string> warnings;                // batches that failed to expand
    double seconds = 0.0;
};

CityExportReport exportCityGltf(const cells::BatchCatalog& catalog,
                                const render::TerminalMeshLibrary& library, const CityExportOptions& options);

} // namespace hexlod::apps
