#version 450 core
// LOD3 and the LOD3 -> LOD2 blend: each entry of the LOD3 draw lists as one screen rectangle
// bounding the projection of its mesh bounds. The fragments ray-cast that box and then the
// shape's baked views (impostor_terminal.frag), writing the depth they find. Pure LOD2 entries
// have lists of their own: impostor_wall.* draws them with the GL's depth, which the GL can
// test before shading (a shader that writes depth is tested after it, on every covered pixel),
// so LOD3 entries that what was drawn before them hides are dropped whole (depth_tiles.glsl).
#include "gpu_types.h"
#include "frame.glsl"
#include "draw_list_entry.glsl"
#include "depth_tiles.glsl"

layout(std430, binding = 8) readonly buffer ShapeBuffer { GpuShape shapes[]; };

uniform mat4 inverseViewProjection;

noperspective out vec3 vRay; // camera-relative point on the pixel's view ray
flat out vec3 vCorner, vAxisX, vAxisY, vAxisZ, vScope;
flat out vec3 vBoxLo, vBoxHi; // the mesh bounds in scope metres
flat out uint vShape;
flat out float vTransition;
flat out float vNearestDepth; // window depth of the box's nearest point

void main() {
    DrawEntry e = drawEntry(pulledRecord());
    vBoxLo = shapes[e.shape].boundsMin.xyz * e.scope;
    vBoxHi = shapes[e.shape].boundsMax.xyz * e.scope;

    // The box's corners in clip space: one corner plus the three edge vectors (projection is
    // linear before the divide). The rectangle bounds the box clipped to the near plane (in
    // reversed-Z, where clip z reaches w): its corners in front, and where its edges cross the
    // plane. A box reaching past the camera would otherwise cover the whole screen, and
    // rasterising near terminals' full-screen rectangles was most of LOD3's time.
    mat3 axes = mat3(e.axisX, e.axisY, e.axisZ);
    vec3 extent = vBoxHi - vBoxLo;
    vec4 origin = viewProjection * vec4(e.corner + axes * vBoxLo, 1.0);
    vec4 edges[3] = vec4[](viewProjection * vec4(e.axisX * extent.x, 0.0), viewProjection * vec4(e.axisY * extent.y, 0.0),
                           viewProjection * vec4(e.axisZ * extent.z, 0.0));
    vec2 lo = vec2(1.0), hi = vec2(-1.0);
    // The window depth of the box's nearest point (reversed-Z: the largest), which is a corner:
    // depth is monotonic in view distance. A box crossing the near plane reaches depth 1.
    float nearest = 0.0;
    for (int c = 0; c < 8; ++c) {
        vec4 p = origin + ((c & 4) != 0 ? edges[0] : vec4(0.0)) + ((c & 2) != 0 ? edges[1] : vec4(0.0)) +
                 ((c & 1) != 0 ? edges[2] : vec4(0.0));
        float inFront = p.w - p.z; // >= 0: on the visible side of the near plane
        if (inFront >= 0.0 && p.w > 0.0) {
            lo = min(lo, p.xy / p.w);
            hi = max(hi, p.xy / p.w);
            nearest = max(nearest, p.z / p.w);
        } else {
            nearest = 1.0;
        }
        // The three edges leaving this corner toward higher corners.
        for (int axis = 0; axis < 3; ++axis) {
            if ((c & (4 >> axis)) != 0) continue;
            vec4 q = p + edges[axis];
            float qFront = q.w - q.z;
            if ((inFront >= 0.0) == (qFront >= 0.0)) continue;
            vec4 cut = mix(p, q, inFront / (inFront - qFront));
            if (cut.w <= 0.0) continue;
            lo = min(lo, cut.xy / cut.w);
            hi = max(hi, cut.xy / cut.w);
        }
    }
    lo = max(lo, vec2(-1.0));
    hi = min(hi, vec2(1.0));
    vNearestDepth = nearest;
    if (behindDepthTiles(lo, hi, nearest)) {
        countDropped();
        gl_Position = kNoVertex;
        return;
    }
    int corner = pulledCorner();
    vec2 ndc = vec2((corner & 1) != 0 ? hi.x : lo.x, (corner & 2) != 0 ? hi.y : lo.y);
    // Any depth inside the frustum: the fragment shader writes the surface's own. At a constant
    // clip depth the unprojected point is linear across the screen, so vRay interpolates exactly.
    gl_Position = vec4(ndc, 0.5, 1.0);
    vec4 ray = inverseViewProjection * vec4(ndc, 0.5, 1.0);
    vRay = ray.xyz / ray.w;
    vCorner = e.corner;
    vAxisX = e.axisX;
    vAxisY = e.axisY;
    vAxisZ = e.axisZ;
    vScope = e.scope;
    vShape = e.shape;
    vTransition = e.transition;
}
