#version 450 core
// Turns the cull pass's counters into indirect draw commands, one thread per shape: an indexed
// instanced draw of its mesh over the LOD4 entries, and indexed draws of a rectangle per LOD2
// entry and per LOD3 entry (quad_indices.h), which pull their entry by gl_VertexID.
#include "gpu_types.h"
#include "cull_shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = 3) readonly buffer ShapeBuffer { uvec4 shapes[]; };
layout(std430, binding = 4) readonly buffer CounterBuffer { uvec4 counters[]; };
layout(std430, binding = 6) readonly buffer MeshBuffer { uvec4 meshes[]; }; // index count, first index, base vertex
// DrawElementsIndirectCommands (5 uints): per shape for LOD4, then per shape for LOD2, then per
// shape for LOD3 (gpu_cull.h).
layout(std430, binding = 7) writeonly buffer CommandBuffer { uint commands[]; };
layout(std430, binding = 15) readonly buffer Lod3BaseBuffer { uint lod3Bases[]; };

uniform uint shapeCount;

void main() {
    uint shape = gl_GlobalInvocationID.x;
    if (shape >= shapeCount) return;
    uvec4 info = shapes[shape], count = counters[shape], mesh = meshes[shape];
    uint at = shape * 5u;
    commands[at + 0u] = mesh.x;
    commands[at + 1u] = count.x;
    commands[at + 2u] = mesh.y;
    commands[at + 3u] = mesh.z;
    // The coarse shape of a shape without impostor fills that shape's lists from the back
    // (cull_shared.h).
    commands[at + 4u] = info.z == HEXLOD_COARSE_SHAPE ? info.x + info.y - count.x : info.x;
    // Six indices a rectangle from the start of the quad indices, the base vertex four a
    // record before the first entry.
    at = shapeCount * 5u + shape * 5u;
    commands[at + 0u] = 6u * count.w;
    commands[at + 1u] = 1u;
    commands[at + 2u] = 0u;
    commands[at + 3u] = 4u * (info.x + info.y - count.w);
    commands[at + 4u] = 0u;
    at += shapeCount * 5u;
    commands[at + 0u] = 6u * count.z;
    commands[at + 1u] = 1u;
    commands[at + 2u] = 0u;
    commands[at + 3u] = 4u * lod3Bases[shape];
    commands[at + 4u] = 0u;
}
