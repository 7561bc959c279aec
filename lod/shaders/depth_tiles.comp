#version 450 core
// The farthest depth (reversed-Z: the smallest value) of each tile of the frame's depth
// target, every sample of every pixel included (depth_tiles.h). A thread reduces a square of
// `tilesAcross` x `tilesAcross` tiles: llvmpipe pays for each workgroup, so small tiles share
// one (DepthTiles::build).
layout(local_size_x = 8, local_size_y = 8) in;

#ifdef MULTISAMPLED
uniform sampler2DMS depthTarget;
#else
uniform sampler2D depthTarget;
#endif
uniform uint tileSize;
uniform uint tilesAcross;
uniform uint samples;
layout(r32f, binding = 0) writeonly uniform image2D tiles;

float farthestOf(ivec2 tile, ivec2 size) {
    ivec2 lo = tile * int(tileSize);
    ivec2 hi = min(lo + int(tileSize), size);
    float farthest = 1.0;
#ifdef MULTISAMPLED
    for (int y = lo.y; y < hi.y; ++y)
        for (int x = lo.x; x < hi.x; ++x)
            for (int s = 0; s < int(samples); ++s)
                farthest = min(farthest, texelFetch(depthTarget, ivec2(x, y), s).r);
#else
    // Two by two pixels a lookup, at their shared corner: two thirds of the time of one pixel a
    // lookup on llvmpipe. Past the target's last row or column the sampler clamps, repeating
    // pixels already counted.
    vec2 pixel = 1.0 / vec2(size);
    for (int y = lo.y; y < hi.y; y += 2)
        for (int x = lo.x; x < hi.x; x += 2) {
            vec4 d = textureGather(depthTarget, vec2(x + 1, y + 1) * pixel);
            farthest = min(farthest, min(min(d.x, d.y), min(d.z, d.w)));
        }
#endif
    return farthest;
}

void main() {
#ifdef MULTISAMPLED
    ivec2 size = textureSize(depthTarget);
#else
    ivec2 size = textureSize(depthTarget, 0);
#endif
    ivec2 first = ivec2(gl_GlobalInvocationID.xy) * int(tilesAcross);
    ivec2 count = imageSize(tiles);
    for (int y = 0; y < int(tilesAcross); ++y)
        for (int x = 0; x < int(tilesAcross); ++x) {
            ivec2 tile = first + ivec2(x, y);
            if (all(lessThan(tile, count))) imageStore(tiles, tile, vec4(farthestOf(tile, size)));
        }
}
