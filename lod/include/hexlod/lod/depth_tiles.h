// The farthest depth of each kDepthTileSize-pixel square tile of the frame's depth target,
// built by one compute pass (depth_tiles.comp) once the opaque and impostor passes are drawn.
// A later pass whose fragments write their own depth (the tree billboards), and so cannot be
// rejected before shading, tests its whole rectangle against it instead (depth_tiles.glsl).
#pragma once

#include "hexlod/render/shader_program.h"

#include <cstdint>
#include <string>

namespace hexlod::lod {

constexpr uint32_t kDepthTileSize = 16;

class DepthTiles {
public:
    DepthTiles() = default;
    ~DepthTiles();
    DepthTiles(const DepthTiles&) = delete;
    DepthTiles& operator=(const DepthTiles&) = delete;

    // Tiles for a width x height target of `samples` samples per pixel.
    bool init(uint32_t width, uint32_t height, uint32_t samples, std::string& error);
    // Reduces `depthTexture` (the target's depth attachment) into the tiles. No draw may be
    // in progress into it; the result is visible to later texture fetches.
    void build(uint32_t depthTexture) const;
    // Binds the tiles to texture unit `unit` and sets depth_tiles.glsl's uniforms of
    // `program`, which must be in use; `enabled` false makes every rectangle visible.
    void bind(const render::ShaderProgram& program, uint32_t unit, bool enabled) const;
    uint64_t byteSize() const { return uint64_t(columns_) * rows_ * sizeof(float); }

private:
    render::ShaderProgram program_;
    uint32_t texture_ = 0, columns_ = 0, rows_ = 0, samples_ = 1;
};

} // namespace hexlod::lod
