#version 450 core
// Ray-casts one LOD3 terminal's impostor: the pixel's view ray enters the terminal's box (or
// misses it, within the box's screen rectangle) and is carried into the shape's nominal space
// (undoing the scope's stretch), then LOD3 blends the four nearest views with parallax
// correction; in the LOD3 -> LOD2 transition it mixes in the central view on the wall plane.
// The surface found writes its own depth, so impostors and geometry intersect correctly.
#include "frame.glsl"

uniform sampler2DArray impostorAlbedo, impostorNormalDepth;
uniform usampler2D impostorTableViews;
uniform sampler2D impostorTableWeights;
uniform uvec4 impostorLayout;
#include "impostor_views.glsl"
#include "depth_tile_lookup.glsl"

uniform uint centralView;        // the view nearest the wall's normal
uniform uint parallaxIterations; // LOD3

layout(std430, binding = 8) readonly buffer ShapeBuffer { GpuShape shapes[]; };
layout(std430, binding = 9) readonly buffer SphereBuffer { vec4 spheres[]; }; // per layer: centre, radius

noperspective in vec3 vRay;
flat in vec3 vCorner, vAxisX, vAxisY, vAxisZ, vScope;
flat in vec3 vBoxLo, vBoxHi;
flat in uint vShape;
flat in float vTransition;
flat in float vNearestDepth;
uniform uint alphaToCoverage;
layout(location = 0) out vec4 colour;

// Scope-relative metres to the shape's nominal metres, per axis (a flat axis stays flat).
vec3 toNominal(vec3 local, vec3 nominal) {
    vec3 unit = vec3(local.x / vScope.x, local.y / vScope.y, vScope.z > 0.0 ? local.z / vScope.z : 0.0);
    return unit * nominal;
}

void main() {
    if (fragmentBehindDepthTile(gl_FragCoord.xy, vNearestDepth)) discard;
    GpuShape shape = shapes[vShape];
    uint layer = uint(shape.nominalSize.w);
    vec4 sphere = spheres[layer];
    mat3 toScope = transpose(mat3(vAxisX, vAxisY, vAxisZ));
    // Slab test in scope metres; a flat box (zero depth) is its one plane. The camera inside
    // the box, or the box behind it, shows nothing, as the box's back faces would not.
    vec3 rayScope = toScope * vRay, fromScope = toScope * -vCorner;
    vec3 inverse = 1.0 / mix(rayScope, vec3(1e-20), lessThan(abs(rayScope), vec3(1e-20)));
    vec3 t0 = (vBoxLo - fromScope) * inverse, t1 = (vBoxHi - fromScope) * inverse;
    vec3 near = min(t0, t1), far = max(t0, t1);
    float enter = max(max(near.x, near.y), near.z), leave = min(min(far.x, far.y), far.z);
    if (enter > leave || enter < 0.0) discard;
    vec3 boxEntry = vRay * enter; // camera-relative
    vec3 entry = toNominal(toScope * (boxEntry - vCorner), shape.nominalSize.xyz);
    vec3 direction = toNominal(toScope * normalize(boxEntry), shape.nominalSize.xyz);
    vec3 forward = -normalize(direction);
    vec3 q = (entry - sphere.xyz) / sphere.w;
    vec3 rayOrigin = q - dot(q, forward) * forward;

    // The LOD2 end of the blend: the central view, sampled where the ray meets the wall plane
    // (z = 0 nominal). Pure LOD2 entries are drawn by impostor_wall.*.
    float blend = vTransition;
    vec4 albedo = vec4(0.0), normalDepth = vec4(0.0, 0.0, 0.0, -1.0);
    if (blend > 0.0) {
        vec3 viewForward = impostorViewDirection(centralView), right, up;
        impostorBasis(viewForward, impostorLayout.w, right, up);
        float along = abs(direction.z) > 1e-6 ? -entry.z / direction.z : 0.0;
        vec3 onWall = (entry + along * direction - sphere.xyz) / sphere.w;
        vec2 uv = vec2(dot(onWall, right), dot(onWall, up));
        albedo = impostorSample(impostorAlbedo, layer, centralView, uv);
        normalDepth = vec4(impostorSample(impostorNormalDepth, layer, centralView, uv).xyz, dot(onWall - rayOrigin, forward));
    }
    if (blend < 1.0) {
        uvec4 views;
        vec4 weights;
        impostorViews(forward, views, weights);
        vec4 nd;
        vec4 a = impostorReconstruct(layer, rayOrigin, forward, views, weights, 4u, parallaxIterations, nd);
        if (blend > 0.0) {
            // Coverage-weighted, as two overlapping layers of paint: where one LOD shows nothing
            // (alpha 0, depth -1) the other's colour, normal and depth are kept as they are, so
            // the mix never invents a surface between the two.
            float wa = (1.0 - blend) * a.a, wb = blend * albedo.a, w = wa + wb;
            float share = w > 0.0 ? wb / w : 0.0;
            normalDepth = mix(nd, normalDepth, share);
            albedo = vec4(mix(a.rgb, albedo.rgb, share), mix(a.a, albedo.a, blend));
        } else {
            albedo = a;
            normalDepth = nd;
        }
    }
    // With multisampling, coverage becomes the sample mask (alpha to coverage); else a cutout.
    if (albedo.a < (alphaToCoverage != 0u ? 0.02 : 0.5)) discard;

    // The surface back in camera-relative world space, for lighting, fog and depth.
    vec3 surfaceNominal = sphere.xyz + sphere.w * (rayOrigin + normalDepth.w * forward);
    vec3 nominal = shape.nominalSize.xyz;
    vec3 unit = vec3(surfaceNominal.x / nominal.x, surfaceNominal.y / nominal.y,
                     nominal.z > 0.0 ? surfaceNominal.z / nominal.z : 0.0);
    vec3 world = vCorner + vAxisX * (unit.x * vScope.x) + vAxisY * (unit.y * vScope.y) + vAxisZ * (unit.z * vScope.z);
    vec4 clip = viewProjection * vec4(world, 1.0);
    gl_FragDepth = clamp(clip.z / clip.w, 0.0, 1.0); // reversed-Z, zero-to-one clip depth
    vec3 n = mat3(vAxisX, vAxisY, vAxisZ) * scopeNormal(normalize(normalDepth.xyz), nominal, vScope);
    colour = vec4(shade(albedo.rgb, n, world), alphaToCoverage != 0u ? albedo.a : 1.0);
}
