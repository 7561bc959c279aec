#version 450 core
// Trees too small on screen for their billboard (tree_size.glsl) as one point each: the
// average colour and coverage of the species' nearest view (TreePass's view averages), lit
// with the view's mean normal, the point's area the tree's covered area. A point under a pixel
// is kept with the probability of its area (by tree), so that a field of them covers what
// the trees would on average. The point sits at the sphere's centre and writes no depth of
// its own, so the GL tests it before shading.
#include "gpu_types.h"
#include "cull_shared.h"
#include "frame.glsl"

layout(std140, binding = 0) uniform CullFrameBlock { CullFrame cull; };
layout(std430, binding = 9) readonly buffer SphereBuffer { vec4 spheres[]; }; // per species
// Per tree batch, its trees in a row: position relative to the trees' origin, species (-1: none).
layout(std430, binding = 13) readonly buffer BillboardBuffer { vec4 billboardTrees[]; };
// Per species and view: mean albedo and coverage; mean shape-space normal.
layout(std430, binding = 15) readonly buffer ViewAverageBuffer { vec4 viewAverages[]; };

uniform sampler2DArray impostorAlbedo, impostorNormalDepth;
uniform usampler2D impostorTableViews;
uniform sampler2D impostorTableWeights;
uniform uvec4 impostorLayout;
#include "impostor_views.glsl"
#include "tree_size.glsl"
#include "coverage_hash.glsl"

uniform uint allBillboards;
flat out vec3 vColour;

const vec4 kNoPoint = vec4(2.0, 2.0, 2.0, 1.0);

void main() {
    vec4 tree = billboardTrees[gl_VertexID];
    gl_PointSize = 1.0;
    if (tree.w < 0.0 || (allBillboards == 0u && !treeIsBillboard(tree.xyz, cull))) {
        gl_Position = kNoPoint;
        return;
    }
    uint species = uint(tree.w);
    vec4 sphere = spheres[species];
    vec3 centre = tree.xyz + cull.trees.yzw + sphere.xyz;
    if (!treeIsPoint(tree.xyz, cull.trees.yzw, sphere)) {
        gl_Position = kNoPoint;
        return;
    }
    uvec4 views;
    vec4 weights;
    impostorViews(-normalize(centre), views, weights);
    uint entry = 2u * (species * impostorLayout.x * impostorLayout.x + views.x);
    vec4 albedo = viewAverages[entry];
    vec3 normal = viewAverages[entry + 1u].xyz;
    // The sphere's diameter on screen, shrunk to the area the tree covers in it.
    float side = 2.0 * sphere.w * treeScreenScale / length(centre) * sqrt(albedo.a);
    if (side < 1.0 && coverageHash(uint(gl_VertexID)) >= side * side) {
        gl_Position = kNoPoint;
        return;
    }
    gl_PointSize = max(side, 1.0);
    vColour = shade(albedo.rgb, length(normal) > 0.0 ? normalize(normal) : -normalize(centre), centre);
    gl_Position = viewProjection * vec4(centre, 1.0);
}
