#version 450 core
// The farthest depth (reversed-Z: the smallest value) of each tile of the frame's depth
// target, every sample of every pixel included, one thread per tile (depth_tiles.h).
layout(local_size_x = 8, local_size_y = 8) in;

#ifdef MULTISAMPLED
uniform sampler2DMS depthTarget;
#else
uniform sampler2D depthTarget;
#endif
uniform uint tileSize;
uniform uint samples;
layout(r32f, binding = 0) writeonly uniform image2D tiles;

void main() {
    ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(tile, imageSize(tiles)))) return;
    ivec2 lo = tile * int(tileSize);
#ifdef MULTISAMPLED
    ivec2 size = textureSize(depthTarget);
#else
    ivec2 size = textureSize(depthTarget, 0);
#endif
    ivec2 hi = min(lo + int(tileSize), size);
    float farthest = 1.0;
    for (int y = lo.y; y < hi.y; ++y)
        for (int x = lo.x; x < hi.x; ++x) {
#ifdef MULTISAMPLED
            for (int s = 0; s < int(samples); ++s) farthest = min(farthest, texelFetch(depthTarget, ivec2(x, y), s).r);
#else
            farthest = min(farthest, texelFetch(depthTarget, ivec2(x, y), 0).r);
#endif
        }
    imageStore(tiles, tile, vec4(farthest));
}
