#version 450 core
// Shades interpolated albedo and normal: LOD4 meshes, tree geometry and base volumes.
#include "frame.glsl"

in vec3 vNormal;
in vec3 vAlbedo;
in vec3 vPosition;
layout(location = 0) out vec4 colour;

void main() {
    vec3 n = normalize(gl_FrontFacing ? vNormal : -vNormal);
    colour = vec4(shade(vAlbedo, n, vPosition), 1.0);
}
