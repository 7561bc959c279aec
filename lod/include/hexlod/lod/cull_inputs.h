// What the cull and LOD pass works on, the same for the GPU pass and its CPU reference: the
// resident batches in view, the shape table, and the frame constants built from the camera
// and the LOD profile.
#pragma once

#include "hexlod/cells/frustum.h"
#include "hexlod/grammar/terminal_set.h"
#include "hexlod/lod/cull_shared.h"
#include "hexlod/lod/page_bounds.h"
#include "hexlod/scene/scene_config.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>
#include <vector>

namespace hexlod::lod {

struct CullBatchInput {
    const grammar::TerminalSet* set = nullptr;    // its records and counts per shape
    const std::vector<uint32_t>* pages = nullptr; // where the arena holds its records (TerminalArena)
    glm::dvec3 cellOrigin{0.0};                   // world, what record positions are relative to
    uint32_t shapeBase = 0;                       // global index of its grammar's shape 0
    // Per page, its bounds: the GPU pass skips pages wholly outside the frustum, behind the
    // occlusion tiles, facing away or of trees drawn as billboards (selectCullPages). Null:
    // every page is culled terminal by terminal. The CPU reference never skips a page, so
    // that tests comparing the two also check that skipping loses no visible terminal.
    const std::vector<PageBounds>* pageBounds = nullptr;
};

struct CullInputs {
    std::vector<CullBatchInput> batches;
    uint32_t shapeCount = 0;            // global shapes
    std::vector<uint8_t> shapeImpostor; // per global shape: 1 when it has an impostor
    std::vector<uint8_t> shapeTree;     // per global shape: 1 when it is part of a tree
    // Per global shape, its coarser mesh (meshShape in cull_shared.h): xyz how far it lies from
    // the shape's mesh per unit-scope axis, w the coarse shape or -1. Empty: none has one. The
    // passes use it through coarseTable.
    std::vector<glm::vec4> shapeCoarse;
    // The most records the draw lists may hold (GpuCull::maxListRecords, the GL's largest
    // storage block). The arena fits in it, so the shapes' own lists always do; the coarse
    // shapes' own lists (DrawListLayout) are left out where they would not.
    uint64_t maxListRecords = std::numeric_limits<uint64_t>::max();
    // By tree id: the tree's position relative to the trees' origin (xyz) and its species (w);
    // needed when a shape is a tree shape. treeBuffer is the same on the GPU.
    const std::vector<glm::vec4>* trees = nullptr;
    uint32_t treeBuffer = 0;
    shared::CullFrame frame{};
    glm::dvec3 camera{0.0};
    // The occlusion test's tiles (frame.occlusion, setOcclusion): the texture the GPU pass
    // reads, and the same values on the CPU, row by row from the bottom, for the CPU
    // reference and for skipping hidden pages whole. Both or neither.
    uint32_t occlusionTexture = 0;
    const std::vector<float>* occlusionTiles = nullptr;
};

// Frame constants: the frustum's planes relative to the camera, and the distances from which
// LOD3 and LOD2 are enough by screen-space error (3D Tiles: sse = geometricError * viewport
// height / (distance * 2 tan(fovY / 2)); a LOD is enough once sse <= maxScreenSpaceError).
// `impostors` false forces LOD4 everywhere (the all-LOD4 reference).
shared::CullFrame makeCullFrame(const cells::Frustum& frustum, const scene::LodProfile& profile, double fovY,
                                uint32_t viewportHeight, double transitionBand, bool impostors);

// Sets frame.trees: trees within `billboardDistance` of the camera are geometry, farther ones
// billboards (a negative distance: never billboards).
void setTreeCut(shared::CullFrame& frame, double billboardDistance, const glm::dvec3& treeOrigin,
                const glm::dvec3& camera);

// Lets LOD4 terminals draw their shape's coarser mesh where its deviation projects under the
// profile's error bound (frame.coarseMeshes); the all-LOD4 reference leaves it off.
void setCoarseMeshes(shared::CullFrame& frame, const scene::LodProfile& profile, double fovY,
                     uint32_t viewportHeight);

// Turns the occlusion test on in `frame` (see occlusionRect in cull_shared.h): the camera's
// axes and projection, and a grid of `columns` x `rows` tiles of `tilePixels` pixels over a
// `width` x `height` viewport.
void setOcclusion(shared::CullFrame& frame, const glm::dvec3& forward, const glm::dvec3& up, double fovY,
                  double nearPlane, double farPlane, uint32_t width, uint32_t height, uint32_t columns,
                  uint32_t rows, uint32_t tilePixels);

// Pixels one metre spans at one metre's distance, for a vertical field of view `fovY`.
double screenScale(double fovY, uint32_t viewportHeight);

// The distance from which a LOD of geometric error `error` is enough.
double lodDistance(double geometricError, const scene::LodProfile& profile, double fovY,
                   uint32_t viewportHeight);

// Per-shape layout of the draw lists: list capacity per shape is the number of its terminals
// in the pages the pass culls; bases are their prefix sums. The coarse shape of a shape without
// impostor shares the lists of the shape it serves (same base and capacity, not counted in the
// total); that of a shape with one has its own, as long as the served shape's terminals in the
// pages that may hold LOD4 entries (pageMayHoldLod4).
// LOD3 entries have lists of their own, in a buffer of their own, so that the LOD3 and LOD2
// passes each walk only their entries (a software rasteriser runs a vertex shader's every
// branch for every vertex): per shape with an impostor, its terminals in the pages that may
// hold LOD3 entries (pageMayHoldLod3). They never exceed the draw lists' total.
struct DrawListLayout {
    std::vector<uint32_t> base, capacity; // per global shape
    uint64_t total = 0;
    std::vector<uint32_t> lod3Base, lod3Capacity; // per global shape
    uint64_t lod3Total = 0;
};

// The pages the GPU pass culls terminal by terminal, one uvec4 each: batch index, first arena
// record, records, 0; and the draw-list layout for their terminals. Every page of every batch
// but those whose bounds (page_bounds.h) lie wholly outside the frustum, face away from the
// camera or lie behind the occlusion tiles, and those whose terminals are all parts of trees
// drawn as billboards.
struct CullPages {
    std::vector<glm::uvec4> pages;
    DrawListLayout layout;
    uint64_t terminals = 0;           // in those pages
    uint64_t skippedTerminals = 0;    // in the pages left out
    uint64_t occludedTerminals = 0;   // of those, in pages the occlusion tiles hide
    uint64_t facingAwayTerminals = 0; // of those, in pages facing away (pageFacesAway)
    uint64_t billboardTerminals = 0;  // of those, in pages of trees drawn as billboards
};
CullPages selectCullPages(const CullInputs& inputs);

// inputs.shapeCoarse as both passes use it with `layout`: a shape with an impostor whose coarse
// shape has no lists of its own (no page within LOD3's distance, or they would not fit within
// inputs.maxListRecords) draws its full mesh.
std::vector<glm::vec4> coarseTable(const CullInputs& inputs, const DrawListLayout& layout);

} // namespace hexlod::lod
