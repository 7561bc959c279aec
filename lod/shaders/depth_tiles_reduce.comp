#version 450 core
// One coarser level of the depth tiles (depth_tiles.h): each tile holds the farthest depth
// (reversed-Z: the smallest value) of the two by two finer tiles under it, so that it hides
// a primitive only where all of them do. The finer level's size is even (DepthTiles pads the
// grid), so every finer tile lies under exactly one coarser tile.
layout(local_size_x = 8, local_size_y = 8) in;

layout(r32f, binding = 0) readonly uniform image2D finer;
layout(r32f, binding = 1) writeonly uniform image2D coarser;

void main() {
    ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(tile, imageSize(coarser)))) return;
    ivec2 lo = tile * 2;
    float farthest = min(min(imageLoad(finer, lo).r, imageLoad(finer, lo + ivec2(1, 0)).r),
                         min(imageLoad(finer, lo + ivec2(0, 1)).r,
                             imageLoad(finer, lo + ivec2(1, 1)).r));
    imageStore(coarser, tile, vec4(farthest));
}
