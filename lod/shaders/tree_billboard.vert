#version 450 core
// One billboard per tree that the frame's tree cut (treeIsBillboard, shared with the cull pass)
// leaves to its species impostor: a camera-facing square over the impostor's bounding sphere,
// blending four views (as LOD3) or, beyond LOD2's distance, showing the nearest (as LOD2);
// smaller on screen than tree_size.glsl's limit, a point instead (tree_point.vert). It is
// dropped whole when what the frame drew before hides it (depth_tiles.glsl), and its fragments
// where that hides their tile: the fragment shader writes its depth, so the GL cannot reject
// hidden fragments before shading them.
#include "gpu_types.h"
#include "cull_shared.h"
#include "frame.glsl"

layout(std140, binding = 0) uniform CullFrameBlock { CullFrame cull; };
layout(std430, binding = 9) readonly buffer SphereBuffer { vec4 spheres[]; }; // per species

#include "pulled_quad.glsl"
#include "depth_tiles.glsl"
#include "tree_size.glsl"

// Per tree batch, its trees in a row: position relative to the trees' origin, species (-1: none).
layout(std430, binding = 13) readonly buffer BillboardBuffer { vec4 billboardTrees[]; };
uniform uint allBillboards;

out vec3 vPosition;
flat out vec3 vBase;
flat out uint vSpecies;
flat out uint vOneView; // beyond LOD2's distance: the nearest view alone, as LOD2 draws facades
// Window depth of the sphere's nearest point (2: none, so no fragment is dropped).
flat out float vNearestDepth;

void main() {
    vec4 tree = billboardTrees[pulledRecord()];
    if (tree.w < 0.0 || (allBillboards == 0u && !treeIsBillboard(tree.xyz, cull))) {
        gl_Position = kNoVertex;
        return;
    }
    vSpecies = uint(tree.w);
    vec4 sphere = spheres[vSpecies];
    vBase = tree.xyz + cull.trees.yzw;
    vec3 centre = vBase + sphere.xyz;
    if (treeIsPoint(tree.xyz, cull.trees.yzw, sphere)) { // the point pass draws it
        gl_Position = kNoVertex;
        return;
    }
    vOneView = uint(dot(centre, centre) >= cull.lodDistance.y);
    vec3 toCamera = -normalize(centre);
    vec3 up = abs(toCamera.z) > 0.999 ? vec3(0, 1, 0) : vec3(0, 0, 1);
    vec3 right = normalize(cross(up, toCamera));
    up = cross(toCamera, right);
    // The square's screen rectangle, and the depth of the sphere's nearest point along the
    // view axis: the tree's surface lies behind it. Skipped when the sphere reaches the near
    // plane or a corner is behind the camera.
    vec2 lo = vec2(1e30), hi = vec2(-1e30);
    vec3 forward = vec3(cull.viewForward);
    bool projectable = depthTilesEnabled != 0u && dot(centre, forward) - sphere.w > cull.viewForward.w;
    for (int c = 0; c < 4; ++c) {
        vec2 at = vec2(float(c & 1), float(c >> 1)) * 2.0 - 1.0;
        vec4 clip = viewProjection * vec4(centre + (at.x * right + at.y * up) * sphere.w, 1.0);
        projectable = projectable && clip.w > 0.0;
        lo = min(lo, clip.xy / clip.w);
        hi = max(hi, clip.xy / clip.w);
    }
    vec4 nearest = viewProjection * vec4(centre - forward * sphere.w, 1.0);
    vNearestDepth = projectable ? nearest.z / nearest.w : 2.0;
    if (projectable && behindDepthTiles(lo, hi, vNearestDepth)) {
        countDropped();
        gl_Position = kNoVertex;
        return;
    }
    int vertex = pulledCorner();
    vec2 corner = vec2(float(vertex & 1), float(vertex >> 1)) * 2.0 - 1.0;
    vPosition = centre + (corner.x * right + corner.y * up) * sphere.w;
    gl_Position = viewProjection * vec4(vPosition, 1.0);
}
