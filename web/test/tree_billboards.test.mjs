// TreeBillboards' cut (src/render/tree_billboards.js) with occlusion: a far tree is a billboard
// for the cut whether or not the occlusion tiles hide it, but a hidden one is not drawn, and a
// new occlusion image recomputes the cut.
import assert from 'node:assert/strict';
import test from 'node:test';
import * as THREE from 'three';

import { TreeQuads } from '../src/render/tree_quads.js';
import { TreeBillboards } from '../src/render/tree_billboards.js';

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

const species = {
    generation: 0,
    species: [{ impostor: { centre: [0, 0, 5], radius: 4 } }],
    speciesOf: () => 0,
    makeMesh: (s, capacity) => new TreeQuads(new THREE.MeshBasicMaterial(), capacity),
};

test('hidden billboards stay billboards for the cut but are not drawn', () => {
    const trees = new TreeBillboards(treeSet([[0, 50], [0, 300], [0, 400]]), species);
    assert.equal(trees.gpuBytes, 3 * (12 + 4) + 3 * 68, 'bases and species, and a quad per tree');
    const spheres = [];
    const occlusion = (version) => ({ version, hidesSphere: (x, y, z, r) => (spheres.push([x, y, z, r]), y > 350) });
    trees.updateCut([0, 0, 0], 100, occlusion(1));
    assert.equal(trees.isBillboard(100), false, 'the near tree is terminals');
    assert.ok(trees.isBillboard(101) && trees.isBillboard(102), 'both far trees are billboards');
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
