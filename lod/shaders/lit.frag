#version 450 core
// Shades LOD4 meshes (tree parts among them): interpolated albedo and normal, and the fog
// their vertices computed. A back face shows only where a mesh is drawn two-sided (its
// vertices chose the back's albedo), lit by the other side of the normal.
#include "frame.glsl"

in vec3 vNormal;
in vec3 vAlbedo;
in float vFog;
layout(location = 0) out vec4 colour;

void main() {
    vec3 n = normalize(gl_FrontFacing ? vNormal : -vNormal);
    colour = vec4(shadeFogged(vAlbedo, n, vFog), 1.0);
}
