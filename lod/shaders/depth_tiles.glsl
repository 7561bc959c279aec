// Whether a screen rectangle lies wholly behind what the frame has drawn so far, from the
// farthest depth of each tile (depth_tiles.comp). Needs frame.glsl (the viewport).
#include "depth_tile_lookup.glsl"
uniform uint depthTileCount; // which count a dropped rectangle adds to (TileTest)
layout(std430, binding = 14) buffer DroppedBuffer { uint droppedRectangles[]; };

// Counts a rectangle dropped, once for its six pulled vertices (pulled_quad.glsl).
void countDropped() {
    if (uint(gl_VertexID) % 6u == 0u) atomicAdd(droppedRectangles[depthTileCount], 1u);
}

uniform uint depthTileLevels;  // each a coarser level of tiles (DepthTiles::texture)
uniform uint depthTileLookups; // kDepthTileLookups: more tiles than this count as visible

// `ndcLo`, `ndcHi`: the rectangle's corners in normalised device coordinates; `nearest`: the
// window depth (reversed-Z) of its nearest point. A large rectangle is tested on the finest
// level that covers it in at most depthTileLookups tiles: a coarse tile's depth is the
// farthest of the tiles under it, so it hides the rectangle only where all of them do.
bool behindDepthTiles(vec2 ndcLo, vec2 ndcHi, float nearest) {
    if (depthTilesEnabled == 0u) return false;
    // The tiles over the viewport (the texture's grid is padded past it).
    ivec2 grid = (ivec2(viewport.xy) + int(depthTileSize) - 1) / int(depthTileSize);
    vec2 scale = viewport.xy * 0.5 / float(depthTileSize);
    ivec2 lo = clamp(ivec2(floor((ndcLo + 1.0) * scale)), ivec2(0), grid - 1);
    ivec2 hi = clamp(ivec2(floor((ndcHi + 1.0) * scale)), ivec2(0), grid - 1);
    int level = 0;
    while ((hi.x - lo.x + 1) * (hi.y - lo.y + 1) > int(depthTileLookups) &&
           level + 1 < int(depthTileLevels)) {
        lo >>= 1;
        hi >>= 1;
        ++level;
    }
    if ((hi.x - lo.x + 1) * (hi.y - lo.y + 1) > int(depthTileLookups)) return false;
    for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x)
            // Depth GREATER passes nearer fragments: any tile whose farthest depth is not
            // nearer than the rectangle's nearest point may show it.
            if (texelFetch(depthTiles, ivec2(x, y), level).r <= nearest) return false;
    return true;
}
