// Trees far from the camera as billboards (thesis §7.4): every tree of the scene by id (its
// position and species, which the cull pass also reads to drop the terminals of billboard
// trees), pulled per tree batch by vertex id (pulled_quad.glsl); each billboard faces the
// camera and ray-casts its species' full-sphere impostor, so it shows the right view from any
// direction, from above included. Within LOD2's distance it blends four views and writes the
// depth of the tree it shows; beyond, it shows the nearest view flat on its plane, so that the
// GL rejects its hidden fragments before shading them (tree_billboard.vert). It covers the
// screen rectangle of its species' box (the tree's own bounds), within its sphere's square.
// A tree too small on screen for its billboard to show more than an average colour is a
// point instead (tree_size.glsl, tree_view_averages.h). A batch's trees lie in chunks of neighbours, each
// with its bounds: chunks outside the frustum, behind the occlusion tiles or wholly inside the
// tree cut are not drawn at all, and a chunk wholly on one side of the point size is drawn by
// that form alone.
#pragma once

#include "hexlod/cells/batch_catalog.h"
#include "hexlod/impostor/impostor_textures.h"
#include "hexlod/lod/cull_shared.h"
#include "hexlod/lod/quad_indices.h"
#include "hexlod/lod/scene_impostors.h"
#include "hexlod/render/shader_program.h"

#include <glm/vec4.hpp>

#include <span>
#include <string>
#include <vector>

namespace hexlod::lod {

// What a frame's far trees are drawn against.
struct TreeFrame {
    const shared::CullFrame* cull = nullptr;            // the frame bound as block 0
    const std::vector<float>* occlusionTiles = nullptr; // CullInputs::occlusionTiles, or null
    float screenScale = 0.0f;                           // pixels one metre spans at one metre's distance
    float pointDiameter = 0.0f; // pixels: a tree's sphere smaller on screen than this is a point
};

class TreePass {
public:
    TreePass() = default;
    ~TreePass();
    TreePass(const TreePass&) = delete;
    TreePass& operator=(const TreePass&) = delete;

    // Collects the scene's trees relative to `origin` and uploads them with the species
    // impostors. A scene without trees allocates nothing. `fitToBoxes`: each billboard covers
    // its species' box on screen (ImpostorAtlas bounds), else its sphere's whole square.
    bool init(const cells::BatchCatalog& catalog, const SceneImpostors* impostors, const glm::dvec3& origin,
              bool fitToBoxes, std::string& error);

    bool empty() const { return trees_.empty(); }
    const glm::dvec3& origin() const { return origin_; }
    const std::vector<glm::vec4>& trees() const { return trees_; } // by tree id: position, species
    uint32_t treeBuffer() const { return byId_; }

    // Chooses what to draw of the far trees of `batches` (a tree batch, and whether all of its
    // trees are far, else those the frame's tree cut makes far), chunks that `frame` rules out
    // left out. Returns the trees submitted to the billboard pass and to the point pass.
    std::pair<uint32_t, uint32_t> prepare(const std::vector<std::pair<uint32_t, bool>>& batches,
                                          const TreeFrame& frame);
    // Draws what prepare() chose: billboards with billboardPrograms(), whose depth tiles and
    // coverage the caller has set, then points. Returns the draws made.
    uint32_t drawBillboards(const TreeFrame& frame);
    uint32_t drawPoints(const TreeFrame& frame);
    // GPU bytes: trees, billboards, species impostors
    uint64_t byteSize() const { return bytes_ + quads_.byteSize(); }
    bool hasImpostors() const { return textures_.layers() > 0; }
    // The billboards' two forms (tree_billboard.vert): blended with their own depth, and flat.
    std::span<const render::ShaderProgram, 2> billboardPrograms() const { return billboardPrograms_; }

private:
    // Up to kTreeChunk neighbouring trees of one batch, relative to origin_.
    struct Chunk {
        glm::vec4 sphere{0.0f}; // holds each tree's billboard (its species' impostor sphere)
        glm::vec4 roots{0.0f};  // holds the trees' positions, which the tree cut measures
        float minRadius = 0.0f, maxRadius = 0.0f; // of its trees' species spheres
        uint32_t first = 0, count = 0;            // in the billboard buffer
    };
    // Ranges of trees (billboard records) for one multi-draw: index 1 for batches whose trees
    // are all far.
    struct Ranges {
        std::vector<int32_t> firsts, counts;
        void add(uint32_t first, uint32_t count);
        void clear() { firsts.clear(), counts.clear(); }
    };
    void buildChunks(const std::vector<glm::vec4>& instances, const std::vector<glm::vec4>& speciesSpheres);
    // One multi-draw per non-empty Ranges: a rectangle a tree (billboards, indexed over
    // quads_) or a point.
    uint32_t drawRanges(const render::ShaderProgram& program, const TreeFrame& frame,
                        const Ranges (&ranges)[2], bool points);

    std::vector<glm::vec4> trees_;
    std::vector<std::pair<uint32_t, uint32_t>> ranges_;      // per catalog batch: first billboard, count
    std::vector<std::pair<uint32_t, uint32_t>> chunkRanges_; // per catalog batch: first chunk, count
    std::vector<Chunk> chunks_;
    // prepare()'s choice, reused frame to frame; billboards by form, then as Ranges says.
    Ranges billboardRanges_[2][2], pointRanges_[2];
    glm::dvec3 origin_{0.0};
    impostor::ImpostorTextures textures_;
    render::ShaderProgram billboardPrograms_[2], pointProgram_;
    uint32_t byId_ = 0, instances_ = 0, spheres_ = 0, boxes_ = 0, viewAverages_ = 0, vao_ = 0;
    uint64_t bytes_ = 0;
    QuadIndices quads_; // the billboards' index buffer
};

} // namespace hexlod::lod
