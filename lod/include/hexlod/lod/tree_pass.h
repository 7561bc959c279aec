// Trees far from the camera as billboards (thesis §7.4): every tree of the scene by id (its
// position and species, which the cull pass also reads to drop the terminals of billboard
// trees), pulled per tree batch by vertex id (pulled_quad.glsl); each billboard faces the
// camera and ray-casts its species' full-sphere impostor, so it shows the right view from any
// direction, from above included, and writes the depth of the tree it shows. A batch's trees
// lie in chunks of neighbours, each with its bounds: chunks outside the frustum, behind the
// occlusion tiles or wholly inside the tree cut are not drawn at all.
#pragma once

#include "hexlod/cells/batch_catalog.h"
#include "hexlod/impostor/impostor_textures.h"
#include "hexlod/lod/cull_shared.h"
#include "hexlod/lod/scene_impostors.h"
#include "hexlod/render/shader_program.h"

#include <glm/vec4.hpp>

#include <string>
#include <vector>

namespace hexlod::lod {

class TreePass {
public:
    TreePass() = default;
    ~TreePass();
    TreePass(const TreePass&) = delete;
    TreePass& operator=(const TreePass&) = delete;

    // Collects the scene's trees relative to `origin` and uploads them with the species
    // impostors. A scene without trees allocates nothing.
    bool init(const cells::BatchCatalog& catalog, const SceneImpostors* impostors, const glm::dvec3& origin,
              std::string& error);

    bool empty() const { return trees_.empty(); }
    const glm::dvec3& origin() const { return origin_; }
    const std::vector<glm::vec4>& trees() const { return trees_; } // by tree id: position, species
    uint32_t treeBuffer() const { return byId_; }

    // Draws the billboards of tree batch `batch` (all of its trees when `allBillboards`, else
    // those the frame's tree cut makes billboards), chunks that `frame` (the one bound as block
    // 0) and `occlusionTiles` (CullInputs::occlusionTiles, or null) rule out left out.
    // Returns the billboards submitted.
    uint32_t draw(uint32_t batch, bool allBillboards, const shared::CullFrame& frame,
                  const std::vector<float>* occlusionTiles);
    void begin(const render::ShaderProgram& program) const;
    uint64_t byteSize() const { return bytes_; } // GPU bytes: trees, billboards, species impostors
    bool hasImpostors() const { return textures_.layers() > 0; }
    const render::ShaderProgram& program() const { return program_; }

private:
    // Up to kTreeChunk neighbouring trees of one batch, relative to origin_.
    struct Chunk {
        glm::vec4 sphere{0.0f};        // holds each tree's billboard (its species' impostor sphere)
        glm::vec4 roots{0.0f};         // holds the trees' positions, which the tree cut measures
        uint32_t first = 0, count = 0; // in the billboard buffer
    };
    void buildChunks(const std::vector<glm::vec4>& instances, const std::vector<glm::vec4>& speciesSpheres);

    std::vector<glm::vec4> trees_;
    std::vector<std::pair<uint32_t, uint32_t>> ranges_;      // per catalog batch: first billboard, count
    std::vector<std::pair<uint32_t, uint32_t>> chunkRanges_; // per catalog batch: first chunk, count
    std::vector<Chunk> chunks_;
    std::vector<int32_t> firsts_, counts_; // the draw's ranges of vertices, reused frame to frame
    glm::dvec3 origin_{0.0};
    impostor::ImpostorTextures textures_;
    render::ShaderProgram program_;
    uint32_t byId_ = 0, instances_ = 0, spheres_ = 0, vao_ = 0;
    uint64_t bytes_ = 0;
};

} // namespace hexlod::lod
