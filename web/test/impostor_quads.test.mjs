// The merged impostor quads (src/render/impostor_quads.js) against the InstancedMesh of
// THREE.PlaneGeometry(2, 2) they replace: the same corners and triangles per quad, each of a
// quad's four vertices carrying its matrix, and InstancedMesh's count and matrix calls.
import assert from 'node:assert/strict';
import test from 'node:test';
import * as THREE from 'three';

import { ImpostorQuads, quadCorners } from '../src/render/impostor_quads.js';

const material = new THREE.MeshBasicMaterial();

function matrix(seed) {
    return new THREE.Matrix4().set(...Array.from({ length: 12 }, (_, i) => seed + i), 0, 0, 0, 1);
}

test('every quad is the plane geometry the instanced mesh drew', () => {
    const plane = new THREE.PlaneGeometry(2, 2);
    const corners = Array.from(plane.attributes.position.array).filter((_, i) => i % 3 !== 2); // x, y
    const quads = new ImpostorQuads(material, 3);
    quads.setMatrixAt(2, matrix(1));
    const positions = quads.geometry.attributes.position.array;
    const index = quads.geometry.index.array;
    for (let q = 0; q < 3; ++q) {
        assert.deepEqual(Array.from(positions.subarray(8 * q, 8 * q + 8)), corners);
        assert.deepEqual(Array.from(index.subarray(6 * q, 6 * q + 6)), Array.from(plane.index.array, (v) => v + 4 * q));
    }
});

test('corners take two bytes a vertex, and the index 16 bits while the vertices allow', () => {
    assert.equal(quadCorners(16384).index.array.BYTES_PER_ELEMENT, 2); // vertices 0 to 65535
    const large = quadCorners(16385);
    assert.equal(large.index.array.BYTES_PER_ELEMENT, 4);
    assert.equal(large.index.array[6 * 16384 + 1], 4 * 16384 + 2, 'the first quad past 16 bits');
    assert.equal(large.attributes.position.itemSize, 2);
    assert.equal(large.attributes.position.array.byteLength, 8 * 16385);
});

test('quads carry a bounding sphere of their own: three.js would compute NaN from two-component corners', () => {
    const quads = new ImpostorQuads(material, 8);
    quads.reserve(5); // a grown geometry keeps it too
    for (const geometry of [quadCorners(4), quads.geometry]) {
        assert.ok(geometry.boundingSphere, 'set, so three.js never computes it');
        assert.deepEqual(geometry.boundingSphere.center.toArray(), [0, 0, 0]);
        assert.equal(geometry.boundingSphere.radius, Infinity);
    }
});

test('a quad matrix reaches all four vertices of its quad, and only those', () => {
    const quads = new ImpostorQuads(material, 3);
    quads.setMatrixAt(1, matrix(1));
    const m = matrix(1).elements; // column-major
    const { quadX, quadY, quadZ } = quads.geometry.attributes;
    for (let v = 0; v < 4; ++v) {
        const at = 16 + 4 * v;
        assert.deepEqual(Array.from(quadX.array.subarray(at, at + 4)), [m[0], m[1], m[2], m[12]]);
        assert.deepEqual(Array.from(quadY.array.subarray(at, at + 4)), [m[4], m[5], m[6], m[13]]);
        assert.deepEqual(Array.from(quadZ.array.subarray(at, at + 4)), [m[8], m[9], m[10], m[14]]);
    }
    assert.ok(quadX.array.subarray(0, 16).every((x) => x === 0));
    assert.ok(quadX.array.subarray(32, 48).every((x) => x === 0));
});

test('count draws that many quads, and needsUpdate spreads the matrices written in bulk', () => {
    const quads = new ImpostorQuads(material, 4);
    assert.equal(quads.count, 4);
    quads.reserve(2);
    quads.instanceMatrix.array.set(matrix(10).elements, 0);
    quads.instanceMatrix.array.set(matrix(20).elements, 16);
    quads.count = 2;
    quads.instanceMatrix.needsUpdate = true;
    assert.equal(quads.geometry.drawRange.count, 12);
    assert.equal(quads.count, 2);
    const { quadX } = quads.geometry.attributes;
    assert.equal(quadX.array[16 * 1 + 4 * 3], matrix(20).elements[0]); // quad 1, vertex 3
    assert.equal(quadX.array[16 * 1 + 4 * 3 + 3], matrix(20).elements[12]);
    quads.count = 9; // beyond the capacity: all four
    assert.equal(quads.count, 4);
    assert.equal(quads.visible, true);
    quads.count = 0;
    assert.equal(quads.geometry.drawRange.count, 0);
    assert.equal(quads.visible, false, 'nothing to draw: no draw');
});

test('vertices grow with the quads drawn, keep what was written, and never pass the capacity', () => {
    const quads = new ImpostorQuads(material, 200);
    assert.equal(quads.geometry.index.count, 0); // nothing drawn yet: no vertices
    const empty = quads.bytes;
    assert.equal(empty, 0, 'no matrices either');
    quads.setMatrixAt(0, matrix(5));
    assert.equal(quads.geometry.index.count / 6, 64);
    assert.equal(quads.instanceMatrix.array.length, 16 * 64, 'the matrices grow with the vertices');
    quads.setMatrixAt(100, matrix(7));
    assert.equal(quads.geometry.index.count / 6, 128);
    assert.equal(quads.instanceMatrix.array.subarray(0, 16).join(), matrix(5).elements.join(), 'matrices kept across the growth');
    assert.equal(quads.geometry.attributes.quadX.array[0], matrix(5).elements[0]); // kept across the growth
    assert.equal(quads.geometry.attributes.quadZ.array[16 * 100 + 3], matrix(7).elements[14]);
    quads.setMatrixAt(199, matrix(9));
    assert.equal(quads.geometry.index.count / 6, 200);
    assert.ok(quads.bytes > empty);
    quads.count = 150;
    assert.equal(quads.count, 150);
});
