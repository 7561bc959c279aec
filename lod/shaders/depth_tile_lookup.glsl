// The depth tiles (depth_tiles.comp: the farthest depth of each tile of what the frame has
// drawn so far), as both stages of a pass that tests against them see them: the vertex
// stage drops rectangles whole (depth_tiles.glsl), the fragment stage the fragments of tiles
// drawn nearer than the whole primitive.
uniform sampler2D depthTiles;
uniform uint depthTileSize;
uniform uint depthTilesEnabled;

// For a fragment shader that writes its own depth (so the GL cannot test it before shading),
// with its gl_FragCoord.xy: whether every sample of the fragment's tile holds depth nearer
// than `nearest`, the window depth (reversed-Z) of the primitive's nearest point, so that none
// of its samples could pass the depth test. Discarding such a fragment first changes no pixel.
bool fragmentBehindDepthTile(vec2 fragCoord, float nearest) {
    if (depthTilesEnabled == 0u) return false;
    return texelFetch(depthTiles, ivec2(fragCoord) / int(depthTileSize), 0).r > nearest;
}
