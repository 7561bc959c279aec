#version 450 core
// LOD3 and LOD2: each impostor entry of the draw lists as the box of its mesh bounds, whose
// fragments then ray-cast into the shape's baked views (impostor_terminal.frag).
#include "gpu_types.h"
#include "frame.glsl"

layout(location = HEXLOD_ATTRIBUTE_INSTANCE_POSITION) in vec3 corner;
layout(location = HEXLOD_ATTRIBUTE_INSTANCE_BUILDING) in float transition;
layout(location = HEXLOD_ATTRIBUTE_INSTANCE_ORIENTATION) in vec4 orientation;
layout(location = HEXLOD_ATTRIBUTE_INSTANCE_SIZE) in vec2 size;
layout(location = HEXLOD_ATTRIBUTE_INSTANCE_SHAPE) in uint shape;
layout(location = HEXLOD_ATTRIBUTE_INSTANCE_DEPTH) in float depthRatio;

layout(std430, binding = 8) readonly buffer ShapeBuffer { GpuShape shapes[]; };

out vec3 vPosition;
flat out vec3 vCorner, vAxisX, vAxisY, vAxisZ, vScope;
flat out uint vShape;
flat out float vTransition;

// The 36 corners of a box's 12 triangles, counter-clockwise from outside.
const int kFaces[36] = int[](0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2,
                             1, 3, 7, 1, 7, 5);

void main() {
    vec4 q = normalize(orientation);
    vAxisX = rotateByQuaternion(q, vec3(1, 0, 0));
    vAxisY = rotateByQuaternion(q, vec3(0, 1, 0));
    vAxisZ = rotateByQuaternion(q, vec3(0, 0, 1));
    vScope = vec3(size, depthRatio * min(size.x, size.y));
    int c = kFaces[gl_VertexID];
    vec3 lo = shapes[shape].boundsMin.xyz, hi = shapes[shape].boundsMax.xyz;
    vec3 unit = vec3((c & 4) != 0 ? hi.x : lo.x, (c & 2) != 0 ? hi.y : lo.y, (c & 1) != 0 ? hi.z : lo.z);
    vec3 position = corner + vAxisX * (unit.x * vScope.x) + vAxisY * (unit.y * vScope.y) + vAxisZ * (unit.z * vScope.z);
    gl_Position = viewProjection * vec4(position, 1.0);
    vPosition = position;
    vCorner = corner;
    vShape = shape;
    vTransition = transition;
}
