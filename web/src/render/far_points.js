// What far buildings' and far trees' points share (building_points.js, tree_points.js), as the
// native lod/shaders/coverage_hash.glsl and point.frag. A point under a pixel is kept with the
// probability of its area, so that a field of them covers on average what the shapes they
// stand for would; the number it is kept by is fixed per point, keyed by its place, or the
// field would shimmer from frame to frame.
export const COVERAGE_HASH_GLSL = /* glsl */ `
// A fixed number in [0, 1) per point, keyed by its place.
float coverageHash(vec3 p) {
    uint i = floatBitsToUint(p.x) ^ (floatBitsToUint(p.y) * 0x9e3779b9u) ^ (floatBitsToUint(p.z) * 0x85ebca6bu);
    i ^= i >> 16;
    i *= 0x7feb352du;
    i ^= i >> 15;
    i *= 0x846ca68bu;
    i ^= i >> 16;
    return float(i >> 8) * (1.0 / 16777216.0);
}
`;

// A point's fragment: its colour, lit in the vertex shader, fogged as three.js fogs.
export const POINT_FRAGMENT = /* glsl */ `
flat in vec3 vColour;
#include <fog_pars_fragment>
void main() {
    gl_FragColor = vec4(vColour, 1.0);
    #include <colorspace_fragment>
    #include <fog_fragment>
}
`;
