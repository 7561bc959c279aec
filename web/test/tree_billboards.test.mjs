// TreeBillboards' cut (src/render/tree_billboards.js): with occlusion, a far tree is far for the
// cut whether or not the occlusion tiles hide it, but a hidden one is not drawn, and a new
// occlusion image recomputes the cut; a far tree small on screen is a point, not a billboard,
// and the cut is recomputed exactly when a tree may change form.
import assert from 'node:assert/strict';
import test from 'node:test';
import * as THREE from 'three';

import { TreeBillboards } from '../src/render/tree_billboards.js';
import { TreePoints } from '../src/render/tree_points.js';
import { TreeQuads } from '../src/render/tree_quads.js';

// Trees of one species on 2 m square footprints centred at the given points (cell-local).
function treeSet(centres) {
    const n = centres.length, x = [], y = [];
    for (const [cx, cy] of centres) {
        x.push(cx - 1, cx + 1, cx + 1, cx - 1);
        y.push(cy - 1, cy - 1, cy + 1, cy + 1);
    }
    return {
        cell: { q: 0, r: 0 }, grammar: 1, parametersPerBuilding: 1, parameters: [new Float32Array(n).fill(7)],
        buildings: {
            count: n, id: Uint32Array.from(centres, (_, i) => 100 + i), firstVertex: Uint32Array.from(centres, (_, i) => 4 * i),
            vertexCount: new Uint32Array(n).fill(4), baseElevation: new Float32Array(n),
        },
        footprints: { x: Float32Array.from(x), y: Float32Array.from(y) },
    };
}

// One species (sphere centred 5 m up, radius 4 m), with or without view averages for points.
function speciesOf({ points }) {
    return {
        generation: 0,
        species: [{ impostor: { centre: [0, 0, 5], radius: 4 } }],
        speciesOf: () => 0,
        makeMesh: (s, capacity) => new TreeQuads(new THREE.MeshBasicMaterial(), capacity),
        hasPoints: () => points,
        makePoints: (capacity) => new TreePoints(new THREE.PointsMaterial(), capacity),
    };
}
const species = speciesOf({ points: false });

test('hidden billboards stay billboards for the cut but are not drawn', () => {
    const trees = new TreeBillboards(treeSet([[0, 50], [0, 300], [0, 400]]), species);
    assert.equal(trees.gpuBytes, 3 * (12 + 4) + 3 * 68, 'bases and species, and a quad per tree');
    const spheres = [];
    const occlusion = (version) => ({ version, hidesSphere: (x, y, z, r) => (spheres.push([x, y, z, r]), y > 350) });
    trees.updateCut([0, 0, 0], 100, occlusion(1));
    assert.equal(trees.isFar(100), false, 'the near tree is terminals');
    assert.ok(trees.isFar(101) && trees.isFar(102), 'both far trees are billboards');
    assert.equal(trees.points, null, 'no points without view averages');
    assert.equal(trees.count, 1);
    assert.equal(trees.occluded, 1);
    // Each far tree's species sphere, relative to the camera.
    assert.deepEqual(spheres, [[0, 300, 5, 4], [0, 400, 5, 4]]);
    const version = trees.version;
    trees.updateCut([0, 0, 0], 100, { version: 2, hidesSphere: () => false });
    assert.equal(trees.count, 2, 'a new image sorts again');
    assert.equal(trees.occluded, 0);
    assert.equal(trees.version, version, 'occlusion does not change the cut');
    // The same image and camera keep the lists.
    trees.updateCut([0, 0, 0], 100, occlusion(1));
    const count = trees.count;
    trees.updateCut([0, 0, 0], 100, occlusion(1));
    assert.equal(trees.count, count);
    assert.equal(trees.occluded, 1);
});

// The drawn points' sphere centres (cell-local) and species.
function drawnPoints(trees) {
    const { position, species } = trees.points.geometry.attributes;
    return Array.from({ length: trees.pointCount }, (_, i) => [...position.array.slice(3 * i, 3 * i + 3), species.array[i]]);
}

test('far trees small on screen are points, the others billboards, and each is one of the two', () => {
    // Trees 50, 300, 400 and 900 m north; a point past 100 m per metre of diameter: 800 m.
    const trees = new TreeBillboards(treeSet([[0, 50], [0, 300], [0, 400], [0, 900]]), speciesOf({ points: true }));
    assert.equal(trees.gpuBytes, 4 * (12 + 4) + 4 * 68 + 4 * 16, 'bases and species, a quad and a point per tree');
    trees.updateCut([0, 0, 0], 100, null, 100);
    assert.equal(trees.isFar(100), false, 'the near tree is terminals');
    assert.ok([101, 102, 103].every((id) => trees.isFar(id)), 'the others are far');
    assert.equal(trees.count, 2, 'two billboards');
    assert.equal(trees.pointCount, 1, 'one point');
    assert.deepEqual(drawnPoints(trees), [[0, 900, 5, 0]], 'at its sphere centre');
    assert.equal(trees.points.visible, true);
    // Without a point scale every far tree is a billboard.
    trees.updateCut([0, 0, 0], 100, null, 0);
    assert.equal(trees.count, 3);
    assert.equal(trees.pointCount, 0);
    assert.equal(trees.points.visible, false, 'no empty draw');
    // A hidden tree is neither.
    trees.updateCut([0, 0, 0], 100, { version: 1, hidesSphere: (x, y) => y > 850 }, 100);
    assert.equal(trees.pointCount, 0);
    assert.equal(trees.occluded, 1);
});

test('the cut is recomputed when a tree may change form, not before', () => {
    // A point past 100 m per metre of diameter (800 m); far past 100 m.
    const trees = new TreeBillboards(treeSet([[0, 50], [0, 790], [0, 2000]]), speciesOf({ points: true }));
    trees.updateCut([0, 0, 0], 100, null, 100);
    assert.equal(trees.pointCount, 1);
    // The 790 m tree's centre is 790.02 m away: the margin is its 9.98 m to the point threshold.
    assert.ok(Math.abs(trees.margin - (800 - Math.hypot(790, 5))) < 1e-9, `margin ${trees.margin}`);
    // Moving 9 m away keeps the cut (under the margin), 11 m makes it a point.
    trees.updateCut([0, -9, 0], 100, null, 100);
    assert.equal(trees.pointCount, 1, 'under the margin nothing is decided again');
    trees.updateCut([0, -11, 0], 100, null, 100);
    assert.equal(trees.pointCount, 2, 'past it the tree is a point');
    // A far batch with every tree beyond the threshold keeps its cut however the camera hovers.
    const far = new TreeBillboards(treeSet([[0, 3000], [10, 3100]]), speciesOf({ points: true }));
    far.updateCut([0, 0, 0], 0, null, 100);
    assert.equal(far.pointCount, 2);
    const margin = far.margin;
    assert.ok(Math.abs(margin - (Math.hypot(3000, 5) - 800)) < 1e-6, `margin ${margin}: the nearer tree's to 800 m`);
    const version = far.points.geometry.attributes.position.version;
    far.updateCut([0, 1000, 0], 0, null, 100);
    assert.equal(far.points.geometry.attributes.position.version, version, 'moved 1 km of its 2.2 km margin: no new upload');
    // A changed point scale decides again.
    far.updateCut([0, 1000, 0], 0, null, 1000);
    assert.equal(far.pointCount, 0, 'at 8 km per point both are billboards');
    assert.equal(far.count, 2);
});
