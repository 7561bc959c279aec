// Whether a screen rectangle lies wholly behind what the frame has drawn so far, from the
// farthest depth of each tile (depth_tiles.comp). Needs frame.glsl (the viewport).
#include "depth_tile_lookup.glsl"
uniform uint depthTileCount; // which count a dropped rectangle adds to (TileTest)
layout(std430, binding = 14) buffer DroppedBuffer { uint droppedRectangles[]; };

// Counts a rectangle dropped, once for its six pulled vertices (pulled_quad.glsl).
void countDropped() {
    if (uint(gl_VertexID) % 6u == 0u) atomicAdd(droppedRectangles[depthTileCount], 1u);
}

// `ndcLo`, `ndcHi`: the rectangle's corners in normalised device coordinates; `nearest`: the
// window depth (reversed-Z) of its nearest point. A rectangle over more tiles than this is not
// worth the lookups and counts as visible.
const int kMaxDepthTileLookups = 64;

bool behindDepthTiles(vec2 ndcLo, vec2 ndcHi, float nearest) {
    if (depthTilesEnabled == 0u) return false;
    ivec2 grid = textureSize(depthTiles, 0);
    vec2 scale = viewport.xy * 0.5 / float(depthTileSize);
    ivec2 lo = clamp(ivec2(floor((ndcLo + 1.0) * scale)), ivec2(0), grid - 1);
    ivec2 hi = clamp(ivec2(floor((ndcHi + 1.0) * scale)), ivec2(0), grid - 1);
    if ((hi.x - lo.x + 1) * (hi.y - lo.y + 1) > kMaxDepthTileLookups) return false;
    for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x)
            // Depth GREATER passes nearer fragments: any tile whose farthest depth is not
            // nearer than the rectangle's nearest point may show it.
            if (texelFetch(depthTiles, ivec2(x, y), 0).r <= nearest) return false;
    return true;
}
