// The viewer's table of impostor views and weights against the C++ one the native renderer
// uploads (ViewLookup::buildTable at kFacadeTableResolution and kSpeciesTableResolution, written
// by web_golden_payloads), for grids of 8 and 5 on both spheres; and the blend's own rules.
import assert from 'node:assert/strict';
import test from 'node:test';

import { FULL_SPHERE, HEMISPHERE, viewDirection } from '../src/render/impostor_views.js';
import {
    buildViewTable,
    FACADE_TABLE_RESOLUTION,
    layoutTableUniforms,
    nearestViews,
    SPECIES_TABLE_RESOLUTION,
} from '../src/render/view_table.js';
import { goldenJson } from './golden.js';

// A texel's blend as view -> weight over the views that take part: views tied in distance may
// come in either order, and a weight within float noise of 0 counts as 0.
function blendOf(views, weights, at) {
    const blend = new Map();
    for (let k = 0; k < 4; ++k) if (weights[at + k] > 1e-4) blend.set(views[at + k], weights[at + k]);
    return blend;
}

test('the table matches the C++ table texel for texel, at the native resolutions', () => {
    for (const layout of goldenJson('view_layout.json')) {
        const expected = layout.direction_table;
        const resolution = layout.sphere === HEMISPHERE ? FACADE_TABLE_RESOLUTION : SPECIES_TABLE_RESOLUTION;
        assert.equal(resolution, expected.resolution, `${layout.sphere}: the native table's resolution`);
        const table = buildViewTable(layout, resolution);
        let differing = 0;
        for (let t = 0; t < resolution * resolution; ++t) {
            const ours = blendOf(table.views, table.weights, 4 * t);
            const theirs = blendOf(expected.views, expected.weights, 4 * t);
            const same = ours.size === theirs.size && [...theirs].every(([v, w]) => Math.abs((ours.get(v) ?? -1) - w) < 1e-4);
            if (!same && differing++ < 3) console.log(`${layout.sphere} grid ${layout.grid} texel ${t}:`, ours, theirs);
        }
        assert.equal(differing, 0, `${layout.sphere} grid ${layout.grid}: texels that differ`);
    }
});

function directionsOf(grid, sphere) {
    const directions = [];
    for (let v = 0; v < grid * grid; ++v) directions.push(...viewDirection(v, grid, sphere));
    return directions;
}

test('a direction on a view takes that view alone; weights are ordered and sum to 1', () => {
    for (const sphere of [HEMISPHERE, FULL_SPHERE]) {
        const directions = directionsOf(8, sphere);
        for (let v = 0; v < 64; ++v) {
            const { views, weights, count } = nearestViews(viewDirection(v, 8, sphere), directions, sphere);
            assert.equal(views[0], v);
            assert.deepEqual([weights, count], [[1, 0, 0, 0], 1]);
        }
        for (const d of [[0.3, -0.2, 0.93], [0.4, 0.1, -0.9], [0, 0, -1], [-1, 0, 0], [0.577, 0.577, 0.577]]) {
            const l = Math.hypot(...d);
            const { views, weights, count } = nearestViews(d.map((c) => c / l), directions, sphere);
            assert.ok(Math.abs(weights.reduce((a, b) => a + b) - 1) < 1e-12, `${sphere} ${d}: ${weights}`);
            for (let k = 1; k < 4; ++k) assert.ok(weights[k] <= weights[k - 1], `${sphere} ${d}: ${weights}`);
            assert.equal(count, weights.filter((w) => w > 0).length);
            assert.ok(count >= 1 && count <= 4 && views.every((v) => v >= 0 && v < 64));
        }
    }
});

test('behind the wall, the hemisphere blends the rim; fewer than five views blend them all', () => {
    const directions = directionsOf(8, HEMISPHERE);
    assert.deepEqual(nearestViews([0.6, 0, -0.8], directions, HEMISPHERE), nearestViews([1, 0, 0], directions, HEMISPHERE));
    assert.deepEqual(nearestViews([0, 0, -1], directions, HEMISPHERE), nearestViews([0, 0, 1], directions, HEMISPHERE));
    // A 2 x 2 grid: four views, plain inverse distances less the floor.
    const four = directionsOf(2, FULL_SPHERE);
    const { weights, count } = nearestViews([0, 0, 1], four, FULL_SPHERE);
    assert.equal(count, 4);
    weights.forEach((w) => assert.ok(Math.abs(w - 0.25) < 1e-12, `${weights}`));
});

test('a layout grid outside [2, 32] is refused with a reason, not built', () => {
    for (const grid of [0, 1, 33, 1e6, 2.5, NaN, undefined, '8']) {
        assert.throws(() => buildViewTable({ grid, sphere: HEMISPHERE }, 16), RangeError, `grid ${grid}`);
        const failed = [];
        assert.equal(layoutTableUniforms({ grid, sphere: FULL_SPHERE }, 16, failed), null);
        assert.match(failed[0], /outside \[2, 32\]/);
    }
});
