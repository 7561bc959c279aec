#version 450 core
// Base volumes, as VOLUME_SHADING (a define) says:
//   0: plain walls shaded per vertex (the shells under terminal sets): their faces are flat,
//      so the light is the same, and the fog across a face is nearly linear (volume.vert);
//   1: plain, shaded per pixel (the ground: one rectangle out to where the fog is whole);
//   2: LOD0's wall texture (wall_texture.glsl), shaded per pixel;
//   3: LOD0 where the wall texture is its mean on every pixel (lod/wall_texture_mean.h): that
//      mean shaded per vertex, as 0.
// Defines, not uniforms: llvmpipe computes both sides of a choice on a uniform for every
// pixel, so plain walls and the ground paid for the texture they did not show.
#include "frame.glsl"
#include "wall_texture.glsl"

in vec3 vNormal;
in vec3 vAlbedo;
in vec3 vPosition;
in vec3 vLocal;
in vec3 vShaded;
layout(location = 0) out vec4 colour;

void main() {
#if VOLUME_SHADING == 0 || VOLUME_SHADING == 3
    colour = vec4(vShaded, 1.0);
#else
    vec3 n = normalize(gl_FrontFacing ? vNormal : -vNormal);
#if VOLUME_SHADING == 2
    vec3 albedo = wallTexture(vAlbedo, n, vLocal);
#else
    vec3 albedo = vAlbedo;
#endif
    colour = vec4(shade(albedo, n, vPosition), 1.0);
#endif
}
