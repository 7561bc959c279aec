// LOD0's far form in the viewer (src/render/building_points.js): each base volume as one point
// carrying its box's centre, height, footprint area and perimeter and its wall colour at the
// window pattern's mean, and the rule that turns a whole batch into points.
import assert from 'node:assert/strict';
import test from 'node:test';

import { buildBuildingPoints, farAsPoints, largestBuildingDiagonal, makeBuildingPointMaterial, POINTS_UNDER_SSE } from '../src/render/building_points.js';
import { buildExtrudedGeometry, wallColourOf, wallTextureMean } from '../src/render/extruded_mesh.js';
import { makeLights } from '../src/render/lights.js';
import { screenScale } from '../src/stream/lod_policy.js';

// A 10 x 6 m rectangle 8 m tall on a base at 2 m (wall material 3), a two-vertex footprint (no
// volume), and a clockwise L of 4 x 4 m less its 2 x 2 m corner, 3 m tall (wall material 11).
function extrudedSet() {
    return {
        parametersPerBuilding: 1,
        parameters: [Float32Array.of(2, 2, 0)],
        buildings: {
            count: 3, id: Uint32Array.of(42, 43, 44), firstVertex: Uint32Array.of(0, 4, 6), vertexCount: Uint32Array.of(4, 2, 6),
            height: Float32Array.of(8, 5, 3), baseElevation: Float32Array.of(2, 0, 0), wallMaterial: Uint32Array.of(3, 0, 11),
        },
        footprints: {
            x: Float32Array.of(0, 10, 10, 0, 0, 1, 20, 20, 22, 22, 24, 24),
            y: Float32Array.of(0, 0, 6, 6, 0, 0, 0, 4, 4, 2, 2, 0),
        },
    };
}
const { lighting } = makeLights();
const material = makeBuildingPointMaterial(lighting);

// The rectangle's storeys are 2 m (its grammar declares floor_h), the L's the default 3 m.
const grammar = { parameters: [{ name: 'floor_h' }] };

function pointsOf(set) {
    const { attributes } = buildBuildingPoints(set, grammar, material).geometry;
    const at = (name, i) => Array.from(attributes[name].array.slice(3 * i, 3 * i + 3));
    return Array.from({ length: attributes.position.count }, (_, i) => ({
        centre: at('position', i),
        shape: at('pointShape', i),
        wall: at('wallColour', i).map((v) => v / 65535),
    }));
}

test('one point per base volume, at its box centre, with its height, area and perimeter', () => {
    const points = pointsOf(extrudedSet());
    assert.equal(points.length, 2, 'the footprint without a volume has no point, as it has no shell');
    assert.deepEqual(points[0].centre, [5, 3, 6]);
    assert.deepEqual(points[0].shape, [8, 60, 32]);
    // The L winds clockwise: its area still counts positive.
    assert.deepEqual(points[1].centre, [22, 2, 1.5]);
    assert.deepEqual(points[1].shape, [3, 12, 16]);
});

test('as many points as the shells draw buildings', () => {
    const set = extrudedSet();
    const { buildingOfTriangle } = buildExtrudedGeometry(set, { parameters: [] });
    assert.equal(new Set(buildingOfTriangle).size, pointsOf(set).length);
});

test("a point's wall colour is the window pattern's mean over its wall", () => {
    const [rectangle] = pointsOf(extrudedSet());
    const mean = wallTextureMean(wallColourOf(3), 8, 2);
    rectangle.wall.forEach((v, k) => assert.ok(Math.abs(v - mean[k]) < 1e-4, `channel ${k}: ${v} against ${mean[k]}`));
    // The pattern sampled finely over an 8 m wall of 2 m storeys and 3 m bays: bare up to half a
    // storey, then windows over 0.56 x 0.52 of each bay, darkened 0.85 of the way to the glass.
    const wall = wallColourOf(3), glass = [0.06, 0.08, 0.11], steps = 800;
    const sampled = [0, 0, 0];
    for (let i = 0; i < steps; ++i)
        for (let j = 0; j < steps; ++j) {
            const x = (3 * (i + 0.5)) / steps, y = (8 * (j + 0.5)) / steps;
            const fx = x / 3, fy = (y / 2) % 1;
            const window = y > 1 && fx >= 0.22 && fx <= 0.78 && fy >= 0.3 && fy <= 0.82 ? 0.85 : 0;
            for (let k = 0; k < 3; ++k) sampled[k] += (wall[k] + (glass[k] - wall[k]) * window) / (steps * steps);
        }
    mean.forEach((v, k) => assert.ok(Math.abs(v - sampled[k]) < 1e-3, `channel ${k}: ${v} against ${sampled[k]}`));
    // No wall, or a storey twice its height: bare.
    assert.deepEqual(wallTextureMean(wall, 0, 3), wall);
    assert.deepEqual(wallTextureMean(wall, 1, 3), wall);
    // Without the grammar (unknown to the viewer), storeys of 3 m.
    const points = buildBuildingPoints(extrudedSet(), undefined, material).geometry.attributes.wallColour.array;
    const fallback = wallTextureMean(wallColourOf(3), 8, 3);
    fallback.forEach((v, k) => assert.ok(Math.abs(points[k] / 65535 - v) < 1e-4));
});

test('the largest box diagonal of a set, 0 without a base volume', () => {
    assert.ok(Math.abs(largestBuildingDiagonal(extrudedSet()) - Math.hypot(10, 6, 8)) < 1e-9);
    const flat = extrudedSet();
    flat.buildings.height = Float32Array.of(0, 0, 0);
    assert.equal(largestBuildingDiagonal(flat), 0);
    assert.equal(pointsOf(flat).length, 0);
});

test('a batch is points once its largest box is under the point size at its nearest distance', () => {
    const view = { viewportHeight: 720, fovY: Math.PI / 3 };
    const profile = { max_screen_space_error: 2 };
    const scale = screenScale(view.viewportHeight, view.fovY);
    assert.ok(Math.abs(scale - 360 / Math.tan(Math.PI / 6)) < 1e-9);
    const diagonal = 20;
    const boundary = (diagonal * scale) / (POINTS_UNDER_SSE * profile.max_screen_space_error);
    assert.equal(farAsPoints(diagonal, boundary * 1.01, view, profile), true);
    assert.equal(farAsPoints(diagonal, boundary * 0.99, view, profile), false);
    assert.equal(farAsPoints(diagonal, 0, view, profile), false, 'the camera inside the cell');
    for (const none of [0, NaN, -1]) assert.equal(farAsPoints(none, 1e9, view, profile), false, `diagonal ${none}`);
    assert.equal(farAsPoints(diagonal, Infinity, view, profile), true);
});

test('the points are not picked: a click on a far building selects the ground', () => {
    const points = buildBuildingPoints(extrudedSet(), grammar, material);
    const hits = [];
    points.raycast(null, hits);
    assert.deepEqual(hits, []);
    assert.equal(material.fog, true, 'fogged as the shells are');
});
