#version 450 core
// One billboard per tree that the frame's tree cut (treeIsBillboard, shared with the cull pass)
// leaves to its species impostor: a camera-facing rectangle over the species' box, within the
// square over the impostor's bounding sphere, blending four views (as LOD3) or, beyond LOD2's
// distance, showing the nearest (as LOD2);
// smaller on screen than tree_size.glsl's limit, a point instead (tree_point.vert). It is
// dropped whole when what the frame drew before hides it (depth_tiles.glsl).
//
// TREE_BILLBOARD_FLAT (a define, 0 or 1) picks which of the two forms a program draws, the
// other's trees dropped here: 0, the blend of four views, whose fragments write the depth of
// the tree they show, so the GL cannot reject hidden ones before shading them (the fragment
// shader drops those whose tile hides them); 1, the nearest view, on the billboard's plane
// through the species' sphere centre, as LOD2 sits on its wall, so that the GL tests each
// fragment's depth before shading it.
#include "gpu_types.h"
#include "cull_shared.h"
#include "frame.glsl"

layout(std140, binding = 0) uniform CullFrameBlock { CullFrame cull; };
layout(std430, binding = 9) readonly buffer SphereBuffer { vec4 spheres[]; }; // per species
// Per species, its box in tree space: two vec4, the lowest corner and the highest (w unused).
layout(std430, binding = 16) readonly buffer BoxBuffer { vec4 speciesBoxes[]; };

#include "pulled_quad.glsl"
#include "depth_tiles.glsl"
#include "tree_size.glsl"

// Per tree batch, its trees in a row: position relative to the trees' origin, species (-1: none).
layout(std430, binding = 13) readonly buffer BillboardBuffer { vec4 billboardTrees[]; };
uniform uint allBillboards;

out vec3 vPosition;
flat out vec3 vBase;
flat out uint vSpecies;
// Window depth of the sphere's nearest point (2: none, so no fragment is dropped).
flat out float vNearestDepth;

// The rectangle, in the billboard's plane (through `centre`, across the view ray; `right`,
// `up` spanning it, offsets from `centre`), that holds what the camera sees of the box
// [lo, hi]: each corner taken along its ray onto the plane. Only pixels whose ray meets the
// box can show the tree; the square's other pixels (half of it or more for the shipped
// species) would ray-cast the impostor only to find nothing. Kept within the square, so it
// never draws more than the square did; the whole square where a corner lies at or behind
// the camera's side of the plane.
void boxRectangle(vec3 lo, vec3 hi, vec3 centre, vec3 right, vec3 up, float radius, out vec2 rectLo,
                  out vec2 rectHi) {
    vec3 ray = normalize(centre);
    float plane = dot(centre, ray);
    rectLo = vec2(radius), rectHi = vec2(-radius);
    for (int c = 0; c < 8; ++c) {
        vec3 corner = mix(lo, hi, vec3(float(c & 1), float((c >> 1) & 1), float(c >> 2)));
        float along = dot(corner, ray);
        if (along <= 1e-3 * plane) {
            rectLo = vec2(-radius), rectHi = vec2(radius);
            return;
        }
        vec3 offset = corner * (plane / along) - centre;
        vec2 at = vec2(dot(offset, right), dot(offset, up));
        rectLo = min(rectLo, at), rectHi = max(rectHi, at);
    }
    rectLo = max(rectLo, vec2(-radius)), rectHi = min(rectHi, vec2(radius));
}

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
    // Beyond LOD2's distance the flat form, as LOD2 draws facades; the other program draws it.
    if (uint(dot(centre, centre) >= cull.lodDistance.y) != uint(TREE_BILLBOARD_FLAT)) {
        gl_Position = kNoVertex;
        return;
    }
    vec3 toCamera = -normalize(centre);
    vec3 up = abs(toCamera.z) > 0.999 ? vec3(0, 1, 0) : vec3(0, 0, 1);
    vec3 right = normalize(cross(up, toCamera));
    up = cross(toCamera, right);
    vec2 rectLo, rectHi;
    vec3 boxLo = vBase + speciesBoxes[2u * vSpecies].xyz;
    vec3 boxHi = vBase + speciesBoxes[2u * vSpecies + 1u].xyz;
    boxRectangle(boxLo, boxHi, centre, right, up, sphere.w, rectLo, rectHi);
    // The rectangle on screen, and the depth of the sphere's nearest point along the view
    // axis: the tree's surface lies behind it. Skipped when the sphere reaches the near plane
    // or a corner is behind the camera.
    vec2 lo = vec2(1e30), hi = vec2(-1e30);
    vec3 forward = vec3(cull.viewForward);
    bool projectable = depthTilesEnabled != 0u && dot(centre, forward) - sphere.w > cull.viewForward.w;
    for (int c = 0; c < 4; ++c) {
        vec2 at = mix(rectLo, rectHi, vec2(float(c & 1), float(c >> 1)));
        vec4 clip = viewProjection * vec4(centre + at.x * right + at.y * up, 1.0);
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
    vec2 corner = mix(rectLo, rectHi, vec2(float(vertex & 1), float(vertex >> 1)));
    vPosition = centre + corner.x * right + corner.y * up;
    gl_Position = viewProjection * vec4(vPosition, 1.0);
}
