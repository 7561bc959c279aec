#version 450 core
// Base volumes in cell-local metres, placed by their cell's camera-relative origin (computed
// in double on the CPU, so a city 1e7 m out renders as steadily as one at the origin); their
// vertices as lod/volume_vertex.h packs them (the ground's as MeshVertex, without elements).
#include "gpu_types.h"
#include "frame.glsl"
#include "wall_colour.glsl"

layout(location = HEXLOD_ATTRIBUTE_POSITION) in vec3 localPosition;
layout(location = HEXLOD_ATTRIBUTE_NORMAL) in vec3 normal;
layout(location = HEXLOD_ATTRIBUTE_ELEMENT) in float element;
layout(location = HEXLOD_ATTRIBUTE_COLOR) in vec4 albedo;

uniform vec3 cellOffset;

out vec3 vNormal;
out vec3 vAlbedo;
out vec3 vPosition;
out vec3 vLocal;
flat out float vElement; // a wall's extruded-set element (render/base_volume_mesh.h), -1 elsewhere
out vec3 vShaded;         // lit and fogged here, for the volumes shaded per vertex (volume.frag)

void main() {
    vPosition = cellOffset + localPosition;
    gl_Position = viewProjection * vec4(vPosition, 1.0);
    vNormal = normal;
    vAlbedo = albedo.rgb;
    vLocal = localPosition;
    vElement = element;
    vec3 n = normalize(normal), shown = albedo.rgb;
#if VOLUME_SHADING == 3
    if (abs(n.z) < 0.5) shown = wallTextureMean(shown); // as wallTexture() does beyond its bays
#endif
    vShaded = shade(shown, n, vPosition);
}
