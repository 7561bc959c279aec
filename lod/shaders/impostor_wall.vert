#version 450 core
// LOD2: each pure LOD2 draw-list entry as its mesh bounds' rectangle on the wall plane (z = 0),
// where the central view lies. The GL rasterises the plane's own depth, so occluded impostors
// fail the depth test before their fragments are shaded. LOD3 entries have lists of their own
// (impostor_terminal.*).
#include "gpu_types.h"
#include "frame.glsl"
#include "draw_list_entry.glsl"

layout(std430, binding = 8) readonly buffer ShapeBuffer { GpuShape shapes[]; };

out vec3 vWorld;   // camera-relative
out vec2 vNominal; // on the wall, in the shape's nominal metres
flat out vec3 vAxisX, vAxisY, vAxisZ, vScope;
flat out uint vShape;

void main() {
    DrawEntry e = drawEntry(pulledRecord());
    GpuShape shape = shapes[e.shape];
    int corner = pulledCorner();
    vec2 unit = vec2((corner & 1) != 0 ? shape.boundsMax.x : shape.boundsMin.x,
                     (corner & 2) != 0 ? shape.boundsMax.y : shape.boundsMin.y);
    vWorld = e.corner + e.axisX * (unit.x * e.scope.x) + e.axisY * (unit.y * e.scope.y);
    gl_Position = viewProjection * vec4(vWorld, 1.0);
    vNominal = unit * shape.nominalSize.xy;
    vAxisX = e.axisX;
    vAxisY = e.axisY;
    vAxisZ = e.axisZ;
    vScope = e.scope;
    vShape = e.shape;
}
