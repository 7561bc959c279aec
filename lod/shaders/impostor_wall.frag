#version 450 core
// LOD2: the shape's central view mapped onto the wall plane, lit with its baked normal. No
// depth write of its own, so the GL tests depth before shading.
#include "frame.glsl"

uniform sampler2DArray impostorAlbedo, impostorNormalDepth;
uniform usampler2D impostorTableViews;
uniform sampler2D impostorTableWeights;
uniform uvec4 impostorLayout;
#include "impostor_views.glsl"

uniform uint centralView; // the view nearest the wall's normal
uniform uint alphaToCoverage;

layout(std430, binding = 8) readonly buffer ShapeBuffer { GpuShape shapes[]; };
layout(std430, binding = 9) readonly buffer SphereBuffer { vec4 spheres[]; }; // per layer: centre, radius

in vec3 vWorld;
in vec2 vNominal;
flat in vec3 vAxisX, vAxisY, vAxisZ, vScope;
flat in uint vShape;
layout(location = 0) out vec4 colour;

void main() {
    GpuShape shape = shapes[vShape];
    uint layer = uint(shape.nominalSize.w);
    vec4 sphere = spheres[layer];
    vec3 viewForward = impostorViewDirection(centralView), right, up;
    impostorBasis(viewForward, impostorLayout.w, right, up);
    vec3 onWall = (vec3(vNominal, 0.0) - sphere.xyz) / sphere.w;
    vec2 uv = vec2(dot(onWall, right), dot(onWall, up));
    vec4 albedo = impostorSample(impostorAlbedo, layer, centralView, uv);
    // With multisampling, coverage becomes the sample mask (alpha to coverage); else a cutout.
    if (albedo.a < (alphaToCoverage != 0u ? 0.02 : 0.5)) discard;
    vec3 stored = normalize(impostorSample(impostorNormalDepth, layer, centralView, uv).xyz);
    vec3 n = mat3(vAxisX, vAxisY, vAxisZ) * scopeNormal(stored, shape.nominalSize.xyz, vScope);
    colour = vec4(shade(albedo.rgb, n, vWorld), alphaToCoverage != 0u ? albedo.a : 1.0);
}
