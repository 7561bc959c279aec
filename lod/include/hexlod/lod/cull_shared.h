// The per-terminal cull and LOD decision (thesis §7.5.3), written once in the common subset of
// C++ and GLSL: terminal_cull.comp includes it through ShaderLibrary, cpu_cull.cpp as a header.
// One source is what lets tests demand *identical* visible sets and LOD choices from the GPU
// pass and the CPU reference: every compared value is computed by the same operations in the
// same order, `precise` in GLSL so the driver may not fuse or reorder them (C++ on x86-64
// without -mfma neither fuses nor reorders).
//
// Rules for this file: types from the aliases below, no references (use HEXLOD_OUT), no
// overloads, float literals with an f suffix (C++ would compute `0.5 * x` in double), no library
// calls that GLSL and glm might compute differently (dot is spelled out).
#ifdef __cplusplus
#pragma once
// Angle brackets: the shader library expands only #include "..." and leaves these to GLSL
// preprocessing, which skips them with the rest of this block.
#include <hexlod/render/gpu_types.h>

#include <glm/glm.hpp>

#include <bit>
#include <cmath>
#include <cstdint>

namespace hexlod::lod::shared {
using uint = uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using gpu::GpuTerminal;
inline float uintBitsToFloat(uint bits) {
    return std::bit_cast<float>(bits);
}
inline int asSigned(uint bits) {
    return int32_t(bits);
}
using std::floor;
using std::sqrt;
#define HEXLOD_PRECISE
#define HEXLOD_OUT(type) type&
#define HEXLOD_FN inline
#else
#define HEXLOD_PRECISE precise
#define HEXLOD_OUT(type) out type
#define HEXLOD_FN
int asSigned(uint bits) {
    return int(bits);
}
#endif

// Frame constants of the cull pass (a std140 uniform block; every member a vec4).
struct CullFrame {
    vec4 planes[6];   // camera-relative frustum planes: inside when dot(xyz, p) + w >= 0
    vec4 lodDistance; // x, y: squared distances from which LOD3, LOD2 are enough; z: relative
                      // transition band; w: 1 when impostors may be used at all
    vec4 trees;       // x: squared distance from which a tree is its billboard (< 0: never);
                      // yzw: the origin of tree positions minus the camera
    // The occlusion test (occlusionRect): the camera's axes, the projection and the tiles.
    vec4 viewRight;    // xyz: the camera's right axis; w: the projection's x scale
    vec4 viewUp;       // xyz: its up axis; w: the projection's y scale
    vec4 viewForward;  // xyz: its forward axis; w: the near plane's distance
    vec4 depthMap;     // window depth (reversed-Z) of view distance d: x / d - y; zw: viewport pixels
    vec4 occlusion;    // x, y: tiles across and down (x = 0: no occlusion test); z: tile pixels
    vec4 coarseMeshes; // x: (screen pixels per radian / error bound)^2, 0: full meshes only
};

// Per global shape (std430 uvec4): x, the first slot of its draw lists; y, their capacity
// (LOD4 entries fill from the front, LOD2 entries from the back; LOD3 entries have lists of
// their own, DrawListLayout); z, 1 when it has an impostor, HEXLOD_COARSE_SHAPE for the coarse
// shape (meshShape) of a shape without impostor, whose LOD4 entries fill the lists of the
// shape it serves from the back (the coarse shape of a shape with an impostor has lists of its
// own); w, 1 when it is part of a tree (whose terminal's building id is then the tree's id).
// Counters per shape (uvec4): LOD4 entries, 0, LOD3 and LOD2 entries.
#define HEXLOD_COARSE_SHAPE 2u

// One resident batch, as the pass sees it (std430, 16 bytes).
struct CullBatch {
    vec3 origin;    // the batch's cell origin minus the camera, rounded to float from double
    uint shapeBase; // global index of the batch grammar's shape 0
};

// The records of a batch lie in arena pages of HEXLOD_ARENA_PAGE records; one workgroup culls
// one page, described by a uvec4: batch index, first arena record of the page, records in it, 0.
#define HEXLOD_ARENA_PAGE 64u

// LOD classes written by the pass.
#define HEXLOD_CULLED 0u
#define HEXLOD_LOD2 2u
#define HEXLOD_LOD3 3u
#define HEXLOD_LOD4 4u

HEXLOD_FN float dot3(vec3 a, vec3 b) {
    HEXLOD_PRECISE float d = a.x * b.x + a.y * b.y;
    HEXLOD_PRECISE float e = d + a.z * b.z;
    return e;
}

// IEEE half to float, exactly (GLSL's unpackHalf2x16 is exact too, but one source is safer).
HEXLOD_FN float halfToFloat(uint h) {
    uint sign = (h & 0x8000u) << 16;
    uint exponent = (h >> 10) & 0x1fu;
    uint mantissa = h & 0x3ffu;
    if (exponent == 0u) {
        // Zero or subnormal: mantissa * 2^-24, exact in float.
        HEXLOD_PRECISE float value = float(mantissa) * 5.9604644775390625e-8f;
        return sign != 0u ? -value : value;
    }
    if (exponent == 31u) return uintBitsToFloat(sign | 0x7f800000u | (mantissa << 13));
    return uintBitsToFloat(sign | ((exponent + 112u) << 23) | (mantissa << 13));
}

HEXLOD_FN float snorm16ToFloat(uint bits) {
    HEXLOD_PRECISE float value = float(asSigned(bits << 16) >> 16) / 32767.0f;
    return value < -1.0f ? -1.0f : value;
}

// The terminal's scope axes from its packed quaternion (x, y, z, w as snorm16). The quaternion is
// not renormalised: snorm16 error is 1.5e-5, far below anything culling decides on.
HEXLOD_FN void terminalAxes(GpuTerminal t, HEXLOD_OUT(vec3) axisX, HEXLOD_OUT(vec3) axisY,
                            HEXLOD_OUT(vec3) axisZ) {
    float x = snorm16ToFloat(t.orientation.x & 0xffffu), y = snorm16ToFloat(t.orientation.x >> 16);
    float z = snorm16ToFloat(t.orientation.y & 0xffffu), w = snorm16ToFloat(t.orientation.y >> 16);
    HEXLOD_PRECISE float xx = x * x, yy = y * y, zz = z * z, xy = x * y, xz = x * z, yz = y * z;
    HEXLOD_PRECISE float wx = w * x, wy = w * y, wz = w * z;
    HEXLOD_PRECISE float xAxis0 = 1.0f - 2.0f * (yy + zz), xAxis1 = 2.0f * (xy + wz),
                         xAxis2 = 2.0f * (xz - wy);
    HEXLOD_PRECISE float yAxis0 = 2.0f * (xy - wz), yAxis1 = 1.0f - 2.0f * (xx + zz),
                         yAxis2 = 2.0f * (yz + wx);
    HEXLOD_PRECISE float zAxis0 = 2.0f * (xz + wy), zAxis1 = 2.0f * (yz - wx),
                         zAxis2 = 1.0f - 2.0f * (xx + yy);
    axisX = vec3(xAxis0, xAxis1, xAxis2);
    axisY = vec3(yAxis0, yAxis1, yAxis2);
    axisZ = vec3(zAxis0, zAxis1, zAxis2);
}

// A tree at `treePosition` (relative to the trees' origin) far enough away to be drawn as its
// species billboard: its terminals are culled, and the billboard pass draws it instead. Both
// passes decide with this function, so a tree is always exactly one of the two.
HEXLOD_FN bool treeIsBillboard(vec3 treePosition, CullFrame frame) {
    if (frame.trees.x < 0.0f) return false;
    HEXLOD_PRECISE vec3 p = treePosition + vec3(frame.trees.y, frame.trees.z, frame.trees.w);
    return dot3(p, p) >= frame.trees.x;
}

// Frustum, backface and LOD for one terminal whose corner lies at `corner` relative to the
// camera; `impostors` says whether its shape has an impostor to fall back on, `onWall` whether
// it sits on a facade (a tree part does not: it is seen from every side). `transition` is
// the LOD4 -> LOD3 or LOD3 -> LOD2 blend in [0, 1] (0: this LOD fully), for the draw passes;
// `sphere` the camera-relative sphere it was culled with, for the occlusion test.
HEXLOD_FN uint classifyTerminal(GpuTerminal t, vec3 corner, CullFrame frame, bool impostors, bool onWall,
                                HEXLOD_OUT(float) transition, HEXLOD_OUT(vec4) sphere) {
    transition = 0.0f;
    vec3 axisX, axisY, axisZ;
    terminalAxes(t, axisX, axisY, axisZ);
    float width = halfToFloat(t.size & 0xffffu), height = halfToFloat(t.size >> 16);
    HEXLOD_PRECISE float depth = halfToFloat(t.shapeAndDepth >> 16) * (width < height ? width : height);
    // The scope box spans depth on both sides of the wall plane (meshes recede to t = -1).
    HEXLOD_PRECISE vec3 centre = corner + axisX * (0.5f * width) + axisY * (0.5f * height);
    HEXLOD_PRECISE float radiusSquared = 0.25f * (width * width + height * height + 4.0f * depth * depth);
    HEXLOD_PRECISE float radius = sqrt(radiusSquared);
    sphere = vec4(centre, radius);
    for (int i = 0; i < 6; ++i) {
        HEXLOD_PRECISE float distance = dot3(vec3(frame.planes[i]), centre) + frame.planes[i].w;
        if (distance < -radius) return HEXLOD_CULLED;
    }
    // Backface: the camera (at the origin) behind the plane the shape recedes to sees none of
    // its front, the wall hiding the rest; its protrusion keeps it visible from a little behind
    // the wall plane itself.
    HEXLOD_PRECISE float inFront = -dot3(axisZ, corner);
    if (onWall && inFront < -depth) return HEXLOD_CULLED;
    if (!impostors || frame.lodDistance.w == 0.0f) return HEXLOD_LOD4;
    HEXLOD_PRECISE float distanceSquared = dot3(centre, centre);
    uint lod = distanceSquared >= frame.lodDistance.y   ? HEXLOD_LOD2
               : distanceSquared >= frame.lodDistance.x ? HEXLOD_LOD3
                                                        : HEXLOD_LOD4;
    // Transitions run over the last `band` of each LOD's range, toward the coarser one.
    float threshold = sqrt(lod == HEXLOD_LOD4 ? frame.lodDistance.x : frame.lodDistance.y);
    float start = threshold * (1.0f - frame.lodDistance.z);
    float distance = sqrt(distanceSquared);
    if (lod != HEXLOD_LOD2 && distance > start && threshold > start) {
        transition = (distance - start) / (threshold - start);
    }
    return lod;
}

// The global shape a LOD4 terminal draws with. A shape may have a coarser mesh, a shape of its
// own (`coarse`, per shape: xyz, how far the two meshes lie apart along each unit-scope axis;
// w, the coarse shape, or -1 for none). A terminal draws it once that distance, scaled by its
// scope, projects under the error bound from the centre of its sphere.
HEXLOD_FN uint meshShape(GpuTerminal t, uint shape, vec4 coarse, vec4 sphere, CullFrame frame) {
    if (coarse.w < 0.0f || frame.coarseMeshes.x <= 0.0f) return shape;
    float width = halfToFloat(t.size & 0xffffu), height = halfToFloat(t.size >> 16);
    HEXLOD_PRECISE float depth = halfToFloat(t.shapeAndDepth >> 16) * (width < height ? width : height);
    HEXLOD_PRECISE vec3 error = vec3(coarse.x * width, coarse.y * height, coarse.z * depth);
    HEXLOD_PRECISE float reachSquared = dot3(error, error) * frame.coarseMeshes.x;
    return dot3(vec3(sphere), vec3(sphere)) >= reachSquared ? uint(coarse.w) : shape;
}

// Occlusion (a hierarchical-Z test of one level): before the pass, the frame has drawn its
// opaque base volumes and ground, and reduced their depth to the farthest depth of each tile
// of occlusion.z pixels (DepthTiles). A sphere is hidden when the window depth of its nearest
// point is farther than the farthest depth of every tile its screen rectangle covers.
// occlusionRect finds those tiles and that depth; each caller then compares the tiles it
// holds (a texture on the GPU, a copy on the CPU) with `tiles <= nearestDepth` meaning "may
// show it". False means the sphere cannot be found hidden: no occlusion test this frame, the
// sphere reaches the near plane, or it covers more than `maxTiles` tiles.
// A page of terminals (page_bounds.h) is tested with the same limit, so that a page found
// hidden holds only terminals the test finds hidden: each one's rectangle lies within the
// page's. The loop stops at the first tile that may show the sphere, so near terminals
// that cover many tiles cost little unless they are hidden.
#define HEXLOD_OCCLUSION_MAX_TILES 256u
HEXLOD_FN bool occlusionRect(vec3 centre, float radius, CullFrame frame, uint maxTiles,
                             HEXLOD_OUT(uvec4) tiles, HEXLOD_OUT(float) nearestDepth) {
    tiles = uvec4(0u, 0u, 0u, 0u);
    nearestDepth = 0.0f;
    if (frame.occlusion.x == 0.0f) return false;
    HEXLOD_PRECISE float z = dot3(vec3(frame.viewForward), centre);
    // A centimetre and a part in 1e4 nearer than the sphere: the occluders' rasterised depth
    // and this one are rounded differently.
    HEXLOD_PRECISE float nearZ = z - radius - 0.01f - 1e-4f * z;
    HEXLOD_PRECISE float farZ = z + radius;
    if (!(nearZ > frame.viewForward.w)) return false;
    HEXLOD_PRECISE float x = dot3(vec3(frame.viewRight), centre);
    HEXLOD_PRECISE float y = dot3(vec3(frame.viewUp), centre);
    // Over the box around the sphere, x / z is least at its low x over the nearest z when that
    // x is negative, else over the farthest z; the other bounds likewise.
    HEXLOD_PRECISE float xLo = x - radius, xHi = x + radius, yLo = y - radius, yHi = y + radius;
    HEXLOD_PRECISE float ndcX0 = frame.viewRight.w * (xLo / (xLo < 0.0f ? nearZ : farZ));
    HEXLOD_PRECISE float ndcX1 = frame.viewRight.w * (xHi / (xHi > 0.0f ? nearZ : farZ));
    HEXLOD_PRECISE float ndcY0 = frame.viewUp.w * (yLo / (yLo < 0.0f ? nearZ : farZ));
    HEXLOD_PRECISE float ndcY1 = frame.viewUp.w * (yHi / (yHi > 0.0f ? nearZ : farZ));
    HEXLOD_PRECISE float toTileX = 0.5f * frame.depthMap.z / frame.occlusion.z;
    HEXLOD_PRECISE float toTileY = 0.5f * frame.depthMap.w / frame.occlusion.z;
    HEXLOD_PRECISE float tileX0 = floor((ndcX0 + 1.0f) * toTileX), tileX1 = floor((ndcX1 + 1.0f) * toTileX);
    HEXLOD_PRECISE float tileY0 = floor((ndcY0 + 1.0f) * toTileY), tileY1 = floor((ndcY1 + 1.0f) * toTileY);
    float lastX = frame.occlusion.x - 1.0f, lastY = frame.occlusion.y - 1.0f;
    // Off the screen on one side: the frustum test keeps only spheres that reach it, so
    // clamping keeps the tiles it does cover.
    tileX0 = tileX0 < 0.0f ? 0.0f : (tileX0 > lastX ? lastX : tileX0);
    tileX1 = tileX1 < 0.0f ? 0.0f : (tileX1 > lastX ? lastX : tileX1);
    tileY0 = tileY0 < 0.0f ? 0.0f : (tileY0 > lastY ? lastY : tileY0);
    tileY1 = tileY1 < 0.0f ? 0.0f : (tileY1 > lastY ? lastY : tileY1);
    if (!(tileX1 >= tileX0 && tileY1 >= tileY0)) return false; // not a number on the way
    if ((tileX1 - tileX0 + 1.0f) * (tileY1 - tileY0 + 1.0f) > float(maxTiles)) return false;
    tiles = uvec4(uint(tileX0), uint(tileY0), uint(tileX1), uint(tileY1));
    nearestDepth = frame.depthMap.x / nearZ - frame.depthMap.y;
    return true;
}

#ifdef __cplusplus
} // namespace hexlod::lod::shared
#endif
