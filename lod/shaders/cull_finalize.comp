#version 450 core
// Turns the cull pass's counters into indirect draw commands, one thread per shape: an indexed
// instanced draw of its mesh over the LOD4 entries, and a non-instanced draw of
// six vertices (a screen rectangle) per impostor entry, which pull their entry by gl_VertexID.
#include "gpu_types.h"
#include "cull_shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = 3) readonly buffer ShapeBuffer { uvec4 shapes[]; };
layout(std430, binding = 4) readonly buffer CounterBuffer { uvec4 counters[]; };
layout(std430, binding = 6) readonly buffer MeshBuffer { uvec4 meshes[]; }; // index count, first index, base vertex
// DrawElementsIndirectCommand (5 uints) then DrawArraysIndirectCommand (4 uints), per shape.
layout(std430, binding = 7) writeonly buffer CommandBuffer { uint commands[]; };

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
    at = shapeCount * 5u + shape * 4u;
    commands[at + 0u] = 6u * count.y;
    commands[at + 1u] = 1u;
    commands[at + 2u] = 6u * (info.x + info.y - count.y);
    commands[at + 3u] = 0u;
}
