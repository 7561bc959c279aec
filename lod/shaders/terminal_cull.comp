#version 450 core
// One pass over every terminal of the resident batches in view (thesis §7.5.3, after niagara's
// drawcull.comp): frustum, backface and occlusion culling, the LOD4/LOD3/LOD2 choice and a
// LOD4 terminal's mesh, compacted into per-shape draw lists through atomic counters. One
// workgroup reads one arena page of a batch.
#include "gpu_types.h"
#include "cull_shared.h"

layout(local_size_x = HEXLOD_ARENA_PAGE) in;

layout(std140, binding = 0) uniform CullFrameBlock { CullFrame frame; };
layout(std430, binding = 0) readonly buffer ArenaBuffer { GpuTerminal arena[]; };
layout(std430, binding = 1) readonly buffer BatchBuffer { CullBatch batches[]; };
layout(std430, binding = 2) readonly buffer PageBuffer { uvec4 pages[]; }; // batch, first record, records
layout(std430, binding = 3) readonly buffer ShapeBuffer { uvec4 shapes[]; };
layout(std430, binding = 4) buffer CounterBuffer { uvec4 counters[]; };
layout(std430, binding = 5) writeonly buffer ListBuffer { GpuTerminal lists[]; };
layout(std430, binding = 10) readonly buffer TreeBuffer { vec4 trees[]; }; // by tree id: position, species
layout(std430, binding = 11) buffer OccludedBuffer { uint occludedTerminals; };
layout(std430, binding = 12) readonly buffer CoarseBuffer { vec4 coarse[]; }; // per shape, see meshShape
layout(std430, binding = 13) writeonly buffer Lod3ListBuffer { GpuTerminal lod3Lists[]; };
layout(std430, binding = 15) readonly buffer Lod3BaseBuffer { uint lod3Bases[]; }; // per shape

uniform uint workgroupCount;
uniform sampler2D occlusionTiles; // the farthest depth of each tile, when frame.occlusion.x > 0

bool hiddenByTiles(vec4 sphere) {
    uvec4 rect;
    float nearest;
    if (!occlusionRect(sphere.xyz, sphere.w, frame, HEXLOD_OCCLUSION_MAX_TILES, rect, nearest)) return false;
    for (uint y = rect.y; y <= rect.w; ++y)
        for (uint x = rect.x; x <= rect.z; ++x)
            if (texelFetch(occlusionTiles, ivec2(x, y), 0).r <= nearest) return false;
    return true;
}

void main() {
    uint workgroup = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
    if (workgroup >= workgroupCount) return;
    uvec4 page = pages[workgroup];
    if (gl_LocalInvocationID.x >= page.z) return;
    CullBatch batch = batches[page.x];
    GpuTerminal t = arena[page.y + gl_LocalInvocationID.x];
    uint shape = batch.shapeBase + (t.shapeAndDepth & 0xffffu);
    uvec4 info = shapes[shape];
    if (info.w != 0u && treeIsBillboard(trees[t.building].xyz, frame)) return;
    precise vec3 corner = t.position + batch.origin;
    float transition;
    vec4 sphere;
    uint lod = classifyTerminal(t, corner, frame, info.z != 0u, info.w == 0u, transition, sphere);
    if (lod == HEXLOD_CULLED) return;
    if (hiddenByTiles(sphere)) {
        atomicAdd(occludedTerminals, 1u);
        return;
    }
    // Small on screen, a LOD4 terminal may draw its shape's coarser mesh, a shape of its own.
    if (lod == HEXLOD_LOD4) {
        shape = meshShape(t, shape, coarse[shape], sphere, frame);
        info = shapes[shape];
    }
    // Draw lists carry the camera-relative corner, the global shape id and, in place of the
    // building id, the transition factor (-1 marks LOD2, which has none).
    t.position = corner;
    t.building = floatBitsToUint(lod == HEXLOD_LOD2 ? -1.0 : transition);
    t.shapeAndDepth = (t.shapeAndDepth & 0xffff0000u) | shape;
    if (info.z == HEXLOD_COARSE_SHAPE) {
        lists[info.x + info.y - 1u - atomicAdd(counters[shape].x, 1u)] = t;
    } else if (lod == HEXLOD_LOD4) {
        lists[info.x + atomicAdd(counters[shape].x, 1u)] = t;
    } else if (lod == HEXLOD_LOD3) {
        lod3Lists[lod3Bases[shape] + atomicAdd(counters[shape].z, 1u)] = t;
    } else {
        lists[info.x + info.y - 1u - atomicAdd(counters[shape].w, 1u)] = t;
    }
}
