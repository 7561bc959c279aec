#version 450 core
// LOD4: terminal meshes instanced over the cull pass's draw lists, the instance data read as
// vertex attributes straight from the list records (vertex pulling from buffers costs about 6x
// on llvmpipe). In the last part of its range a terminal flattens toward its wall, so that the
// switch to its impostor (LOD3) does not pop its depth. The lighting (frame.glsl's, fog
// included) is computed per vertex and its colour interpolated: the pass is bound by
// llvmpipe's triangle setup, whose cost grows with the values interpolated (seven as normal,
// albedo and fog, three as a colour), and on the faceted meshes most shapes are, whose vertex
// normals are their faces', it is the same colour (docs/BENCHMARKS.md, "Leaner curtain walls,
// LOD4 lit per vertex").
// A two-sided mesh's triangle (lod/shape_geometry.h, drawn with `twoSided` set) shows the
// colour of the side the camera sees, lit from that side: its vertex normals are its face's,
// so the sign of the normal against the view ray at a vertex is the triangle's facing, as the
// rasteriser finds it.
#include "gpu_types.h"
#include "frame.glsl"

layout(location = HEXLOD_ATTRIBUTE_POSITION) in vec3 unitPosition;
layout(location = HEXLOD_ATTRIBUTE_NORMAL) in vec3 unitNormal; // unit scope space (ShapeTable)
layout(location = HEXLOD_ATTRIBUTE_COLOR) in vec4 albedo;
layout(location = HEXLOD_ATTRIBUTE_BACK_COLOR) in vec4 backAlbedo;
layout(location = HEXLOD_ATTRIBUTE_INSTANCE_POSITION) in vec3 corner;
layout(location = HEXLOD_ATTRIBUTE_INSTANCE_BUILDING) in float transition;
layout(location = HEXLOD_ATTRIBUTE_INSTANCE_ORIENTATION) in vec4 orientation;
layout(location = HEXLOD_ATTRIBUTE_INSTANCE_SIZE) in vec2 size;
layout(location = HEXLOD_ATTRIBUTE_INSTANCE_DEPTH) in float depthRatio;

uniform bool twoSided;

out vec3 vColour;

void main() {
    vec4 q = normalize(orientation);
    vec3 axisX = rotateByQuaternion(q, vec3(1, 0, 0));
    vec3 axisY = rotateByQuaternion(q, vec3(0, 1, 0));
    vec3 axisZ = rotateByQuaternion(q, vec3(0, 0, 1));
    float depth = depthRatio * min(size.x, size.y) * (1.0 - transition);
    vec3 position = corner + axisX * (unitPosition.x * size.x) + axisY * (unitPosition.y * size.y) +
                    axisZ * (unitPosition.z * depth);
    gl_Position = viewProjection * vec4(position, 1.0);
    // The inverse transpose of diag(size, depth); an axis flattened to nothing (depth at the
    // end of the LOD3 transition) is 1e-4 m, so that it dominates, as in scopeNormal.
    vec3 n = unitNormal / max(vec3(size, depth), vec3(1e-4));
    n = length(n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0);
    vec3 normal = mat3(axisX, axisY, axisZ) * n;
    bool back = twoSided && dot(normal, position) > 0.0;
    vColour = shadeFogged(back ? backAlbedo.rgb : albedo.rgb, back ? -normal : normal, fogAmount(position));
}
