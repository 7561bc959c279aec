// The impostor passes' view of a draw-list entry, pulled by gl_VertexID (pulled_quad.glsl) in
// one non-instanced draw per shape.
// Entries are GpuTerminal records (gpu_types.h) as terminal_cull.comp writes them: the corner
// camera-relative, the building field holding the transition factor (-1: LOD2, no transition),
// the shape field the global shape id.
#include "pulled_quad.glsl"

layout(std430, binding = 5) readonly buffer ListBuffer { GpuTerminal lists[]; };

struct DrawEntry {
    vec3 corner;
    float transition;
    vec3 axisX, axisY, axisZ; // the scope's axes
    vec3 scope;               // the scope's size; z from the depth ratio
    uint shape;
};

DrawEntry drawEntry(uint index) {
    GpuTerminal t = lists[index];
    DrawEntry e;
    e.corner = t.position;
    e.transition = uintBitsToFloat(t.building);
    vec4 q = normalize(vec4(unpackSnorm2x16(t.orientation.x), unpackSnorm2x16(t.orientation.y)));
    e.axisX = rotateByQuaternion(q, vec3(1, 0, 0));
    e.axisY = rotateByQuaternion(q, vec3(0, 1, 0));
    e.axisZ = rotateByQuaternion(q, vec3(0, 0, 1));
    vec2 size = unpackHalf2x16(t.size);
    e.scope = vec3(size, unpackHalf2x16(t.shapeAndDepth >> 16).x * min(size.x, size.y));
    e.shape = t.shapeAndDepth & 0xffffu;
    return e;
}
