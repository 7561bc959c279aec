// Far trees as points (src/render/tree_points.js, tree_view_averages.js): each view's averages
// over its own inner square weighted by coverage, in linear light, and the share of its texels
// a cutout at one half keeps; the rule that makes a tree a point; and the species table the
// shader reads.
import assert from 'node:assert/strict';
import test from 'node:test';

import { makeLights } from '../src/render/lights.js';
import { pointDistancePerMetre, TREE_POINTS_UNDER_SSE, TreePointMaterial, TreePoints, treeIsPoint } from '../src/render/tree_points.js';
import { treeViewAverages } from '../src/render/tree_view_averages.js';
import { screenScale } from '../src/stream/lod_policy.js';

// A 2 x 2 grid of 8-texel views with 2 texels of padding: view v's inner 4 x 4 square holds
// `fill(v, x, y)` ([r, g, b, a, nr, ng, nb]); the padding holds opaque white, which no view
// may count.
function atlas(fill) {
    const layout = { grid: 2, view_resolution: 8, padding: 2 };
    const width = 16, albedo = new Uint8ClampedArray(4 * width * width).fill(255), normal = new Uint8ClampedArray(albedo.length).fill(255);
    for (let v = 0; v < 4; ++v)
        for (let y = 0; y < 4; ++y)
            for (let x = 0; x < 4; ++x) {
                const i = 4 * ((8 * Math.floor(v / 2) + 2 + y) * width + 8 * (v % 2) + 2 + x);
                const [r, g, b, a, nr, ng, nb] = fill(v, x, y);
                albedo.set([r, g, b, a], i);
                normal.set([nr, ng, nb, 200], i);
            }
    return { albedo, normal, width, layout };
}

const linear = (byte) => ((byte / 255 + 0.055) / 1.055) ** 2.4;

test('each view averages its own inner square, weighted by coverage, in linear light, and counts what a cutout keeps', () => {
    // View 0: half its texels opaque sRGB 255 (red), half empty; view 1: a quarter at alpha
    // 128 of sRGB 128 grey; views 2 and 3: empty, and full with two normals.
    const { albedo, normal, width, layout } = atlas((v, x, y) => {
        if (v === 0) return x < 2 ? [255, 0, 0, 255, 255, 128, 128] : [0, 0, 0, 0, 0, 0, 0];
        if (v === 1) return x < 1 ? [128, 128, 128, 128, 128, 128, 255] : [9, 9, 9, 0, 0, 0, 0];
        if (v === 2) return [50, 60, 70, 0, 0, 0, 0];
        return y < 2 ? [0, 255, 0, 255, 255, 128, 128] : [0, 255, 0, 85, 128, 255, 128];
    });
    const out = treeViewAverages(albedo, normal, width, layout);
    assert.equal(out.length, 32);
    const view = (v) => Array.from(out.slice(8 * v, 8 * v + 8));
    const near = (a, b, what) => a.forEach((x, i) => assert.ok(Math.abs(x - b[i]) < 2e-3, `${what}: ${a} against ${b}`));
    near(view(0), [1, 0, 0, 0.5, 1, 0.0039, 0.0039, 0.5], 'half covered red, normal +x, half its texels solid');
    near(view(1), [linear(128), linear(128), linear(128), 0.25 * (128 / 255), 0.0039, 0.0039, 1, 0.25], 'grey at its linear value, a quarter at half coverage (128 of 255: kept by a cutout)');
    near(view(2), [0, 0, 0, 0, 0, 0, 0, 0], 'an empty view averages nothing');
    // View 3: half at alpha 1 with normal +x, half at 1/3 with +y: the normal leans 3:1.
    near(view(3), [0, 1, 0, (1 + 85 / 255) / 2, 0.75, 0.25 + 0.75 * 0.0039, 0.0039, 0.5], 'normals weighted by coverage; a cutout keeps the opaque half');
});

test('an atlas smaller than its layout is refused', () => {
    const { albedo, normal } = atlas(() => [0, 0, 0, 0, 0, 0, 0]);
    assert.throws(() => treeViewAverages(albedo, normal, 16, { grid: 4, view_resolution: 8, padding: 2 }), RangeError);
    assert.throws(() => treeViewAverages(albedo, normal.subarray(4), 16, { grid: 2, view_resolution: 8, padding: 2 }), RangeError);
    assert.throws(() => treeViewAverages(albedo, normal, 16, { grid: 2, view_resolution: 8, padding: 4 }), RangeError, 'no inner square');
    assert.throws(() => treeViewAverages(albedo, normal, 8, { grid: 2, view_resolution: 8, padding: 2 }), RangeError, 'rows narrower than the grid');
});

test('a tree is a point once its sphere spans under the point size', () => {
    const scale = screenScale(720, Math.PI / 3); // 623.5 pixels a metre at 1 m
    const perMetre = pointDistancePerMetre(scale, 2);
    assert.equal(perMetre, scale / (TREE_POINTS_UNDER_SSE * 2));
    // A sphere of radius 5 m spans 10 * 623.5 / d pixels: 4 pixels at 1559 m.
    assert.equal(treeIsPoint(5, 1550, perMetre), false);
    assert.equal(treeIsPoint(5, 1570, perMetre), true);
    assert.equal(treeIsPoint(5, 1e9, 0), false, 'a scale of 0: never');
});

test('the species table holds each species sphere and view averages in its row', () => {
    const { lighting } = makeLights();
    const material = new TreePointMaterial({}, lighting, true);
    const averages = Float32Array.from({ length: 32 }, (_, i) => i / 32);
    material.setSpecies([{ impostor: { centre: [1, 2, 3], radius: 4 }, averages }, undefined, { impostor: { centre: [0, 0, 6], radius: 7 }, averages: null }]);
    const table = material.uniforms.speciesTable.value;
    assert.equal(table.image.width, 9, 'a sphere and two texels per view');
    assert.equal(table.image.height, 3, 'a row per species index');
    const row = (r) => Array.from(table.image.data.slice(4 * 9 * r, 4 * 9 * (r + 1)));
    assert.deepEqual(row(0).slice(0, 4), [1, 2, 3, 4]);
    assert.deepEqual(row(0).slice(4), Array.from(averages));
    assert.deepEqual(row(1), new Array(36).fill(0), 'no species');
    assert.deepEqual(row(2), new Array(36).fill(0), 'no averages: its trees are never points');
    // A new species replaces the table; indices may have holes.
    const sparse = [];
    sparse[3] = { impostor: { centre: [1, 2, 3], radius: 4 }, averages };
    material.setSpecies(sparse);
    const replaced = material.uniforms.speciesTable.value;
    assert.notEqual(replaced, table);
    assert.deepEqual([replaced.image.width, replaced.image.height], [9, 4]);
    assert.deepEqual(Array.from(replaced.image.data.slice(4 * 9 * 3, 4 * 9 * 3 + 4)), [1, 2, 3, 4]);
});

test('a batch of points draws the first points placed, and nothing when none are', () => {
    const points = new TreePoints(null, 3);
    assert.equal(points.visible, false);
    assert.equal(points.bytes, 3 * 16);
    points.place(0, 1, 2, 3, 5);
    points.place(1, 4, 5, 6, 0);
    points.show(2);
    assert.equal(points.visible, true);
    assert.equal(points.geometry.drawRange.count, 2);
    assert.deepEqual(Array.from(points.geometry.attributes.position.array.slice(0, 6)), [1, 2, 3, 4, 5, 6]);
    assert.deepEqual(Array.from(points.geometry.attributes.species.array.slice(0, 2)), [5, 0]);
});
