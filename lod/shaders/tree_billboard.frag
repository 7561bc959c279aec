#version 450 core
// Ray-casts a tree's species impostor (full sphere of views, tree space = world axes at the
// trunk's base), with the same four-view reconstruction as LOD3, or from the nearest view
// alone without parallax beyond LOD2's distance, where a tree is a few pixels and the blend
// would cost four times the texture reads for what no pixel resolves.
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
flat in uint vOneView;
flat in float vNearestDepth;
uniform uint alphaToCoverage;
layout(location = 0) out vec4 colour;

void main() {
    if (fragmentBehindDepthTile(gl_FragCoord.xy, vNearestDepth)) discard;
    vec4 sphere = spheres[vSpecies];
    vec3 forward = -normalize(vPosition);
    vec3 q = (vPosition - vBase - sphere.xyz) / sphere.w;
    vec3 rayOrigin = q - dot(q, forward) * forward;
    uvec4 views;
    vec4 weights;
    impostorViews(forward, views, weights);
    if (vOneView != 0u) weights = vec4(1.0, 0.0, 0.0, 0.0); // the lookup puts the nearest first
    vec4 normalDepth;
    vec4 albedo = impostorReconstruct(vSpecies, rayOrigin, forward, views, weights, vOneView != 0u ? 1u : 4u,
                                      vOneView != 0u ? 0u : 1u, normalDepth);
    // With multisampling, coverage becomes the sample mask (alpha to coverage); else a cutout.
    if (albedo.a < (alphaToCoverage != 0u ? 0.02 : 0.5)) discard;
    vec3 world = vBase + sphere.xyz + sphere.w * (rayOrigin + normalDepth.w * forward);
    vec4 clip = viewProjection * vec4(world, 1.0);
    gl_FragDepth = clamp(clip.z / clip.w, 0.0, 1.0);
    colour = vec4(shade(albedo.rgb, normalize(normalDepth.xyz), world), alphaToCoverage != 0u ? albedo.a : 1.0);
}
