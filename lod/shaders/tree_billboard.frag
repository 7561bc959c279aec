#version 450 core
// Ray-casts a tree's species impostor (full sphere of views, tree space = world axes at the
// trunk's base). TREE_BILLBOARD_FLAT (tree_billboard.vert) picks the form: 0, the same
// four-view reconstruction as LOD3, writing the depth of the surface it finds; 1, beyond
// LOD2's distance, where a tree is a few pixels, the nearest view alone without parallax
// (the blend would cost four times the texture reads for what no pixel resolves), at the
// depth of the billboard's plane, which the GL tests before shading as it does LOD2's.
#include "frame.glsl"

uniform sampler2DArray impostorAlbedo, impostorNormalDepth;
uniform usampler2D impostorTableViews;
uniform sampler2D impostorTableWeights;
uniform uvec4 impostorLayout;
#include "impostor_views.glsl"
#include "depth_tile_lookup.glsl"

layout(std430, binding = 9) readonly buffer SphereBuffer { vec4 spheres[]; };

in vec3 vPosition;
flat in vec3 vBase;
flat in uint vSpecies;
flat in float vNearestDepth;
uniform uint alphaToCoverage;
layout(location = 0) out vec4 colour;

void main() {
#if !TREE_BILLBOARD_FLAT
    if (fragmentBehindDepthTile(gl_FragCoord.xy, vNearestDepth)) discard;
#endif
    vec4 sphere = spheres[vSpecies];
    vec3 forward = -normalize(vPosition);
    vec3 q = (vPosition - vBase - sphere.xyz) / sphere.w;
    vec3 rayOrigin = q - dot(q, forward) * forward;
    uvec4 views;
    vec4 weights;
    impostorViews(forward, views, weights);
#if TREE_BILLBOARD_FLAT
    weights = vec4(1.0, 0.0, 0.0, 0.0); // the lookup puts the nearest first
    const uint viewCount = 1u, iterations = 0u;
#else
    const uint viewCount = 4u, iterations = 1u;
#endif
    vec4 normalDepth;
    vec4 albedo = impostorReconstruct(vSpecies, rayOrigin, forward, views, weights, viewCount, iterations,
                                      normalDepth);
    // With multisampling, coverage becomes the sample mask (alpha to coverage); else a cutout.
    if (albedo.a < (alphaToCoverage != 0u ? 0.02 : 0.5)) discard;
    vec3 world = vBase + sphere.xyz + sphere.w * (rayOrigin + normalDepth.w * forward);
#if !TREE_BILLBOARD_FLAT
    vec4 clip = viewProjection * vec4(world, 1.0);
    gl_FragDepth = clamp(clip.z / clip.w, 0.0, 1.0);
#endif
    colour = vec4(shade(albedo.rgb, normalize(normalDepth.xyz), world), alphaToCoverage != 0u ? albedo.a : 1.0);
}
