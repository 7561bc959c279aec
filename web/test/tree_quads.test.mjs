// The merged tree billboards (src/render/tree_quads.js): a tree's base reaches the four vertices
// of its quad and no other, `show` draws that many and uploads them, and the bytes are what the
// arrays hold.
import assert from 'node:assert/strict';
import test from 'node:test';
import * as THREE from 'three';

import { TreeQuads } from '../src/render/tree_quads.js';

const material = new THREE.MeshBasicMaterial();

test('a base reaches all four vertices of its quad, and only those', () => {
    const quads = new TreeQuads(material, 3);
    assert.equal(quads.count, 0, 'nothing drawn before show');
    assert.equal(quads.visible, false, 'and no empty draw');
    quads.place(1, Float32Array.of(9, 9, 9, 4, 5, 6), 3);
    const bases = quads.geometry.attributes.treeBase;
    assert.deepEqual(Array.from(bases.array.subarray(12, 24)), [4, 5, 6, 4, 5, 6, 4, 5, 6, 4, 5, 6]);
    assert.ok(bases.array.subarray(0, 12).every((x) => x === 0));
    assert.ok(bases.array.subarray(24).every((x) => x === 0));
    const version = bases.version;
    quads.show(2);
    assert.equal(quads.count, 2);
    assert.equal(quads.visible, true);
    assert.equal(quads.geometry.drawRange.count, 12);
    assert.ok(bases.version > version, 'show uploads the bases');
});

test('show stays within the capacity, and the bytes are the arrays', () => {
    const quads = new TreeQuads(material, 4);
    quads.show(9);
    assert.equal(quads.count, 4);
    quads.show(-1);
    assert.equal(quads.count, 0);
    assert.equal(quads.bytes, 4 * (8 + 48 + 12)); // corners, bases, 16-bit index
    assert.equal(new TreeQuads(material, 0).bytes, 0);
});
