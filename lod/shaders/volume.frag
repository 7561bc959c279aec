#version 450 core
// LOD0: a base volume with its wall texture (wall_texture.glsl) where VOLUME_WALL_TEXTURE is
// 1; under terminals (LOD2-4 cells) and on the ground, where it is 0, the walls are plain. A
// define, not a uniform: llvmpipe computes both sides of a choice on a uniform for every
// pixel, so plain walls and the ground paid for the texture they did not show.
#include "frame.glsl"
#include "wall_texture.glsl"

in vec3 vNormal;
in vec3 vAlbedo;
in vec3 vPosition;
in vec3 vLocal;
layout(location = 0) out vec4 colour;

void main() {
    vec3 n = normalize(gl_FrontFacing ? vNormal : -vNormal);
#if VOLUME_WALL_TEXTURE
    vec3 albedo = wallTexture(vAlbedo, n, vLocal);
#else
    vec3 albedo = vAlbedo;
#endif
    colour = vec4(shade(albedo, n, vPosition), 1.0);
}
