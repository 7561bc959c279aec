// The farthest depth of each square tile of the frame's depth target (kDepthTileSize pixels,
// or kVolumeTileSize for the base volume rings' CPU tests), built from what the frame has
// drawn so far (depth_tiles.comp), and coarser levels, each tile the farthest depth of the
// two by two under it (depth_tiles_reduce.comp). The cull pass
// tests every terminal against the finest tiles of the opaque base volumes and ground
// (occlusionRect in cull_shared.h). A later pass whose fragments write their own depth (LOD3
// impostors, tree billboards), and so cannot be rejected before shading, tests each rectangle
// against them in its vertex shader and drops the hidden ones whole (depth_tiles.glsl),
// counting them per pass; the coarser levels let it test a large rectangle in a few lookups:
// late in the thesis street's walk up to 34 LOD3 rectangles a frame span over 64 tiles, 1.3 M
// pixels together, nearly all behind the street's walls.
#pragma once

#include "hexlod/render/buffer_readback.h"
#include "hexlod/render/shader_program.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hexlod::lod {

// The cull pass's tiles, and the vertex-stage tests' (LOD3 impostors, tree billboards).
constexpr uint32_t kDepthTileSize = 16;
// The base volume rings' tiles (CPU tests only, occlusion_tests.h): at 16 pixels a tile on a
// roofline holds sky, so a far building behind the roofs was drawn. At the thesis street
// 4-pixel tiles cut the LOD1 and LOD0 rings' triangles from 11 k and 101 k to 5 k and 27 k a
// frame (docs/BENCHMARKS.md, "Finer tiles for the base volume rings").
constexpr uint32_t kVolumeTileSize = 4;
// The most tiles a vertex stage looks up for one rectangle (depth_tiles.glsl), on the finest
// level that covers it in as few; with more it counts as visible. Levels are added until one
// covers the whole target in as few.
constexpr uint32_t kDepthTileLookups = 64;

// The passes that test against the tiles, each with its count of rectangles dropped.
enum class TileTest : uint32_t { Lod3Impostors, TreeBillboards, Count };

class DepthTiles {
public:
    DepthTiles() = default;
    ~DepthTiles();
    DepthTiles(const DepthTiles&) = delete;
    DepthTiles& operator=(const DepthTiles&) = delete;

    // Tiles of `tileSize` pixels for a width x height target of `samples` samples per pixel.
    bool init(uint32_t width, uint32_t height, uint32_t samples, uint32_t tileSize, std::string& error);
    // Zeroes the counts of dropped rectangles (once a frame, before the passes).
    void clearCounts() const;
    // Reduces `depthTexture` (the target's depth attachment) into the tiles. No draw may be
    // in progress into it; the result is visible to later texture fetches. `coarserLevels`
    // reduces the coarser levels too: only the vertex-stage test reads them (bind), while the
    // cull pass and the CPU copy (read) read the finest alone.
    void build(uint32_t depthTexture, bool coarserLevels);
    // Binds the tiles to texture unit `unit` and the counts, and sets depth_tiles.glsl's
    // uniforms of `program` for pass `test`; `enabled` false makes every rectangle visible.
    // The test reads the coarser levels only when the last build reduced them.
    void bind(const render::ShaderProgram& program, uint32_t unit, TileTest test, bool enabled) const;
    // Rectangles each test dropped since clearCounts(), by TileTest. Waits for the GL.
    std::array<uint32_t, size_t(TileTest::Count)> dropped();
    // The tiles as built last, row by row from the bottom (waits for the GL): the cull pass's
    // occlusion test reads the texture, its CPU side this copy.
    std::vector<float> read() const;
    // The tiles of level `level` as built last, row by row from the bottom (waits for the GL):
    // the padded grid of that level, (paddedColumns() >> level) x (paddedRows() >> level).
    std::vector<float> readLevel(uint32_t level) const;
    // The texture: level 0 the finest tiles, each further level half as many each way. Its
    // grid is padded to a multiple of 2^(levels - 1) each way; a tile past the target holds
    // 1, the nearest depth, so that it never makes a coarser one look farther.
    uint32_t texture() const { return texture_; }
    uint32_t tileSize() const { return tileSize_; }
    uint32_t columns() const { return columns_; }
    uint32_t rows() const { return rows_; }
    uint32_t levels() const { return levels_; }
    uint32_t paddedColumns() const { return paddedColumns_; }
    uint32_t paddedRows() const { return paddedRows_; }
    bool valid() const { return counts_ != 0; }
    uint64_t byteSize() const;

private:
    render::ShaderProgram program_, reduceProgram_;
    uint32_t texture_ = 0, counts_ = 0, columns_ = 0, rows_ = 0, samples_ = 1, tileSize_ = kDepthTileSize;
    uint32_t levels_ = 1, paddedColumns_ = 0, paddedRows_ = 0;
    uint32_t builtLevels_ = 1; // the levels the last build reduced
    render::BufferReadback readback_;
};

} // namespace hexlod::lod
