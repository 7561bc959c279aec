// LOD0's far form, as the native renderer draws it (lod/building_points.h, docs/BENCHMARKS.md
// "The overview: far base volumes in the mesh's order, far buildings as points"): a building a
// pixel or two across shows no more than its roof and its walls blended, so it is one point of
// that colour and of the area it shows the camera, not a shell of a dozen triangles. Software
// renderers pay per triangle and per draw: in the thesis city's overview the extruded cells'
// shells are millions of triangles, each building two or three pixels across.
//
// The viewer decides per batch (farAsPoints): a batch is points once its largest building's box
// stays under the point size at the nearest distance of its cell, so one draw serves the whole
// batch; nearer batches keep their shells.
import * as THREE from 'three';

import { screenSpaceError } from '../stream/lod_policy.js';

import { COVERAGE_HASH_GLSL, POINT_FRAGMENT } from './far_points.js';
import { EXTRUDED_ROOF_COLOUR, extrudedRing, floorHeights, wallColourOf, wallTextureMean } from './extruded_mesh.js';
import { LIGHTING_GLSL, lightingUniforms } from './lights.js';

// How many times the error bound a building's box may span on screen and still be a point:
// the native `buildingPointsUnderSse`.
export const POINTS_UNDER_SSE = 2;

// Whether every building of a batch whose largest box diagonal is `diagonal` metres is under
// the point size at `distance` metres (its cell's nearest) for `view` ({viewportHeight, fovY})
// and the LOD profile.
export function farAsPoints(diagonal, distance, view, profile) {
    if (!(diagonal > 0)) return false;
    return screenSpaceError(diagonal, distance, view.viewportHeight, view.fovY) < POINTS_UNDER_SSE * profile.max_screen_space_error;
}

// Each base volume of an extruded set (the buildings the shells draw: extrudedRing) as
// {i, ring, minX, minY, maxX, maxY, height}.
function* baseVolumes(set) {
    for (let i = 0; i < set.buildings.count; ++i) {
        const ring = extrudedRing(set, i);
        if (!ring) continue;
        let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
        for (const [x, y] of ring) minX = Math.min(minX, x), minY = Math.min(minY, y), maxX = Math.max(maxX, x), maxY = Math.max(maxY, y);
        yield { i, ring, minX, minY, maxX, maxY, height: set.buildings.height[i] };
    }
}

// The largest box diagonal of the set's base volumes, in metres (0 without any).
export function largestBuildingDiagonal(set) {
    let diagonal = 0;
    for (const v of baseVolumes(set)) diagonal = Math.max(diagonal, Math.hypot(v.maxX - v.minX, v.maxY - v.minY, v.height));
    return diagonal;
}

// The set's base volumes as a THREE.Points of `material` (makeBuildingPointMaterial), one
// vertex each at the centre of its box (cell-local) with its height, footprint area and
// perimeter, and its wall colour at the window pattern's mean for its storey height (`grammar`:
// the set's, for its `floor_h`).
export function buildBuildingPoints(set, grammar, material) {
    const floorH = floorHeights(set, grammar);
    const centres = [], shapes = [], walls = [];
    for (const { i, ring, minX, minY, maxX, maxY, height } of baseVolumes(set)) {
        let area = 0, perimeter = 0;
        for (let k = 0; k < ring.length; ++k) {
            const [ax, ay] = ring[k], [bx, by] = ring[(k + 1) % ring.length];
            area += ax * by - bx * ay; // the shoelace formula: twice the signed area
            perimeter += Math.hypot(bx - ax, by - ay);
        }
        centres.push(0.5 * (minX + maxX), 0.5 * (minY + maxY), set.buildings.baseElevation[i] + 0.5 * height);
        shapes.push(height, 0.5 * Math.abs(area), perimeter);
        const mean = wallTextureMean(wallColourOf(set.buildings.wallMaterial[i]), height, floorH ? floorH[i] : undefined);
        walls.push(...mean.map((v) => v * 65535));
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(centres, 3));
    geometry.setAttribute('pointShape', new THREE.Float32BufferAttribute(shapes, 3));
    geometry.setAttribute('wallColour', new THREE.BufferAttribute(Uint16Array.from(walls, Math.round), 3, true));
    geometry.computeBoundingSphere();
    const points = new THREE.Points(geometry, material);
    points.raycast = () => {}; // a click on a far building selects the ground's cell
    return points;
}

const VERTEX = /* glsl */ `
attribute vec3 pointShape; // height, footprint area, footprint perimeter
attribute vec3 wallColour; // linear, the wall texture's mean
uniform float screenScale;
uniform vec3 roofColour;
uniform vec3 sunDirection;
flat out vec3 vColour;
${LIGHTING_GLSL}
#include <fog_pars_vertex>
const float kPi = 3.14159265;

${COVERAGE_HASH_GLSL}
void main() {
    vec3 centre = (modelMatrix * vec4(position, 1.0)).xyz; // camera-relative world (world.js)
    float distance = max(length(centre), 1e-3);
    vec3 toCamera = -centre / distance;
    float across = sqrt(max(1.0 - toCamera.z * toCamera.z, 0.0));
    float roof = pointShape.y * max(toCamera.z, 0.0);
    float walls = pointShape.x * pointShape.z / kPi * across; // the footprint's mean width
    float area = roof + walls; // square metres facing the camera
    float side = sqrt(area) * screenScale / distance;
    gl_PointSize = max(side, 1.0);
    if (side < 1.0 && coverageHash(position) >= side * side) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume
        return;
    }
    vec3 up = vec3(0.0, 0.0, 1.0);
    vec3 facing = across > 1e-4 ? vec3(toCamera.xy / across, 0.0) : up;
    vec3 roofLit = roofColour * lambertLight(up, sunDirection, up);
    vec3 wallLit = wallColour * lambertLight(facing, sunDirection, up);
    vColour = area > 0.0 ? (roof * roofLit + walls * wallLit) / area : roofLit;
    vec4 mvPosition = viewMatrix * vec4(centre, 1.0);
    gl_Position = projectionMatrix * mvPosition;
    #include <fog_vertex>
}
`;

// The one material every batch's points share; `lighting`: World's (lights.js).
export function makeBuildingPointMaterial(lighting) {
    return new THREE.ShaderMaterial({
        vertexShader: VERTEX,
        fragmentShader: POINT_FRAGMENT,
        fog: true,
        uniforms: THREE.UniformsUtils.merge([
            THREE.UniformsLib.fog,
            {
                screenScale: { value: 1 },
                roofColour: { value: new THREE.Vector3(...EXTRUDED_ROOF_COLOUR) },
                sunDirection: { value: lighting.sunDirection },
                ...lightingUniforms(lighting),
            },
        ]),
    });
}
