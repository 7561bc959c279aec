#version 450 core
// LOD0's far form (lod/building_points.h): a building a few pixels across as one point at the
// centre of its box. The point's area is the area the building shows the camera: its roof
// foreshortened, and its walls through the footprint's mean width across the view (perimeter
// over pi, for a convex footprint); its colour is the two blended by those areas, the roof lit
// from above and the walls (LOD0's wall texture at its mean) lit facing the camera. A point
// under a pixel is kept with the probability of its area, as the trees' points are. It writes
// no depth of its own, so the GL tests it before shading.
#include "frame.glsl"
#include "wall_colour.glsl"
#include "coverage_hash.glsl"

struct BuildingPoint {
    vec4 centreHeight; // cell-local centre of its box; its height
    float footprintArea, footprintPerimeter;
    uint wallColour, roofColour; // rgba8
};
layout(std430, binding = 17) readonly buffer BuildingPointBuffer { BuildingPoint points[]; };

uniform vec3 cellOffset;   // the cell's origin, camera-relative
uniform float screenScale; // pixels one metre spans at one metre's distance
uniform uint batch;        // with the building's index, the key of its coverage hash

flat out vec3 vColour;

const vec4 kNoPoint = vec4(2.0, 2.0, 2.0, 1.0);
const float kPi = 3.14159265;

void main() {
    BuildingPoint b = points[gl_VertexID];
    vec3 centre = cellOffset + b.centreHeight.xyz;
    float distance = max(length(centre), 1e-3);
    vec3 toCamera = -centre / distance;
    float across = sqrt(max(1.0 - toCamera.z * toCamera.z, 0.0));
    float roof = b.footprintArea * max(toCamera.z, 0.0);
    float walls = b.centreHeight.w * b.footprintPerimeter / kPi * across;
    float area = roof + walls; // square metres facing the camera
    float side = sqrt(area) * screenScale / distance;
    gl_PointSize = max(side, 1.0);
    if (side < 1.0 && coverageHash(uint(gl_VertexID) ^ (batch * 0x9e3779b9u)) >= side * side) {
        gl_Position = kNoPoint;
        return;
    }
    vec3 facing = across > 1e-4 ? vec3(toCamera.xy / across, 0.0) : vec3(0.0, 0.0, 1.0);
    vec3 roofLit = shade(unpackUnorm4x8(b.roofColour).rgb, vec3(0.0, 0.0, 1.0), centre);
    vec3 wallLit = shade(wallTextureMean(unpackUnorm4x8(b.wallColour).rgb), facing, centre);
    vColour = area > 0.0 ? (roof * roofLit + walls * wallLit) / area : roofLit;
    gl_Position = viewProjection * vec4(centre, 1.0);
}
