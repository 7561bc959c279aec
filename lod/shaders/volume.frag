#version 450 core
// LOD0: a base volume with its wall texture (wall_texture.glsl); under terminals (LOD2-4
// cells) the walls are plain.
#include "frame.glsl"
#include "wall_texture.glsl"

uniform uint texturedWalls;

in vec3 vNormal;
in vec3 vAlbedo;
in vec3 vPosition;
in vec3 vLocal;
layout(location = 0) out vec4 colour;

void main() {
    vec3 n = normalize(gl_FrontFacing ? vNormal : -vNormal);
    vec3 albedo = texturedWalls != 0u ? wallTexture(vAlbedo, n, vLocal) : vAlbedo;
    colour = vec4(shade(albedo, n, vPosition), 1.0);
}
