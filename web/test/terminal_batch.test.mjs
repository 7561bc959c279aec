// TerminalBatch's sorting of a terminal set into LOD4, LOD3 and LOD2 lists (src/render/
// terminal_batch.js): terminals behind their wall (not a tree's parts) or outside the view are
// left out, and the lists are sorted again when the camera has moved or turned enough, or with
// a new occlusion image, not before; a sorted batch's instance buffers grow with what its lists draw.
import assert from 'node:assert/strict';
import test from 'node:test';
import * as THREE from 'three';

import { ImpostorQuads } from '../src/render/impostor_quads.js';
import { TerminalBatch } from '../src/render/terminal_batch.js';
import { degrees, viewAlong } from './views.js';

const material = new THREE.MeshBasicMaterial();
const HALF_ONE = 0x3c00, HALF_TWO = 0x4000, HALF_TENTH = 0x2e66;
const SNORM_SQRT_HALF = 23170; // 0.7071 as snorm16

// One shape's terminals, each a 1 x 2 m terminal on a wall facing -y (scope X = +x, Y = +z,
// Z = -y: a quarter turn about x) with its corner at the given cell-local point.
function setOf(corners) {
    const n = corners.length;
    const records = new Uint32Array(8 * n);
    const positions = new Float32Array(records.buffer);
    corners.forEach(([x, y, z], i) => {
        positions.set([x, y, z], 8 * i);
        records[8 * i + 3] = i; // building
        records[8 * i + 4] = SNORM_SQRT_HALF; // x; y = 0
        records[8 * i + 5] = SNORM_SQRT_HALF << 16; // z = 0; w
        records[8 * i + 6] = HALF_ONE | (HALF_TWO << 16);
        records[8 * i + 7] = HALF_TENTH << 16; // shape 0
    });
    return { cell: { q: 0, r: 0 }, grammar: 0, count: n, countPerShape: new Uint32Array([n]), records, positions };
}

const library = { grammar: { index: 0 }, shapes: [], shape: () => ({ geometry: new THREE.BoxGeometry() }) };
const impostors = { atlasOf: () => ({}), makeMesh: (atlas, lod, capacity) => new ImpostorQuads(material, capacity) };
const distances = { lod3: 100, lod2: 200 };
const turned = (d) => [Math.sin(degrees(d)), Math.cos(degrees(d)), 0];

// The records in the LOD4 list, in order.
function lod4Records(batch) {
    const run = batch.runs[0];
    return Array.from(run.slots[4].subarray(0, run.lod4.count));
}

test('terminals behind their wall or outside the view are left out of every list', () => {
    // Ahead (y = 20), behind the camera and facing away (y = -20), far to the side (x = 60),
    // and ahead beyond the LOD3 and LOD2 distances.
    const batch = new TerminalBatch(setOf([[0, 20, 0], [0, -20, 0], [60, 15, 0], [0, 150, 0], [0, 250, 0]]),
        library, material, impostors);
    batch.updateLod([0, 0, 0], distances, null, viewAlong([0, 1, 0]));
    assert.deepEqual(batch.counts, { 4: 1, 3: 1, 2: 1, culled: 2, coarse: 0, occluded: 0 });
    assert.deepEqual(lod4Records(batch), [0]);
    // Without a view only the one behind its wall is left out.
    const all = new TerminalBatch(setOf([[0, 20, 0], [0, -20, 0], [60, 15, 0]]), library, material, impostors);
    all.updateLod([0, 0, 0], distances);
    assert.deepEqual(all.counts, { 4: 2, 3: 0, 2: 0, culled: 1, coarse: 0, occluded: 0 });
    assert.deepEqual(lod4Records(all), [0, 2]);
    // A tree's parts stand free: the one seen from behind shows its other side.
    const tree = new TerminalBatch(setOf([[0, 20, 0], [0, -20, 0], [60, 15, 0]]), library, material, impostors,
        { freeStanding: true });
    tree.updateLod([0, 0, 0], distances);
    assert.deepEqual(tree.counts, { 4: 3, 3: 0, 2: 0, culled: 0, coarse: 0, occluded: 0 });
    assert.deepEqual(lod4Records(tree), [0, 1, 2]);
});

test('the lists are sorted again once the view turns by half the margin, and not before', () => {
    const batch = new TerminalBatch(setOf([[0, 20, 0], [60, 15, 0]]), library, material, impostors);
    batch.updateLod([0, 0, 0], distances, null, viewAlong([0, 1, 0]));
    const counts = batch.counts;
    batch.updateLod([0, 0, 0], distances, null, viewAlong(turned(4)));
    assert.equal(batch.counts, counts, 'a 4 degree turn keeps the lists');
    // Turned 70 degrees to the right, towards +x: the terminal at x = 60 is in view, the one
    // straight ahead before is not.
    batch.updateLod([0, 0, 0], distances, null, viewAlong(turned(70)));
    assert.deepEqual(batch.counts, { 4: 1, 3: 0, 2: 0, culled: 1, coarse: 0, occluded: 0 });
    assert.deepEqual(lod4Records(batch), [1]);
    // A changed field of view sorts again too, even unturned.
    const wider = { ...viewAlong(turned(70)), key: 'wider' };
    const before = batch.counts;
    batch.updateLod([0, 0, 0], distances, null, wider);
    assert.notEqual(batch.counts, before);
});

test('a shape draws its coarse mesh where the deviation projects under the budget', () => {
    // 1 x 2 m terminals, depth 0.1 m: a deviation of (0.1, 0.05, 1) reaches
    // |(0.1, 0.1, 0.1)| = 0.1732 m, so from 17.32 m at 100 m per metre.
    const coarseGeometry = new THREE.BoxGeometry();
    const coarseLibrary = {
        grammar: { index: 0 },
        shapes: [],
        shape: () => ({ geometry: new THREE.BoxGeometry(), coarse: { geometry: coarseGeometry, deviation: [0.1, 0.05, 1.0], triangles: 12 } }),
    };
    const batch = new TerminalBatch(setOf([[0, 10, 0], [0, 30, 0], [0, 16, 0]]), coarseLibrary, material, null);
    const perMetre = { lod3: 0, lod2: 0, coarse: 100 };
    batch.updateLod([0, 0, 0], perMetre);
    const run = batch.runs[0];
    assert.equal(run.coarse.geometry, coarseGeometry);
    assert.deepEqual(batch.counts, { 4: 3, 3: 0, 2: 0, culled: 0, coarse: 1, occluded: 0 }, 'LOD4 counts the coarse mesh\'s terminals too');
    assert.deepEqual(lod4Records(batch), [0, 2]);
    assert.equal(run.coarse.count, 1);
    assert.equal(batch.recordOf(run.coarse, 0), 1, 'a picked coarse instance names its record');
    // The instance is the record's matrix: its corner at (0, 30, 0).
    assert.deepEqual(Array.from(run.coarse.instanceMatrix.array.subarray(12, 15)), [0, 30, 0]);
    // A smaller error budget (fewer metres per metre of deviation) brings them all back.
    batch.updateLod([0, 0, 0], { ...perMetre, coarse: 10 });
    assert.equal(run.coarse.count, 3);
    assert.equal(run.lod4.count, 0);
    // A shape with an impostor draws it too, up to LOD3's distance, as in the native pass.
    const withImpostor = new TerminalBatch(setOf([[0, 10, 0], [0, 30, 0], [0, 150, 0]]), coarseLibrary, material, impostors);
    withImpostor.updateLod([0, 0, 0], { ...distances, coarse: 100 });
    assert.deepEqual(withImpostor.counts, { 4: 2, 3: 1, 2: 0, culled: 0, coarse: 1, occluded: 0 });
    assert.equal(withImpostor.runs[0].coarse.count, 1);
    assert.equal(withImpostor.recordOf(withImpostor.runs[0].coarse, 0), 1);
});

test('terminals the occlusion tiles hide are left out, and each new image sorts the lists again', () => {
    const batch = new TerminalBatch(setOf([[0, 20, 0], [0, 150, 0], [0, 250, 0]]), library, material, impostors);
    // Stand-in tiles hiding everything past y = 100, and the spheres they were asked about.
    const asked = [];
    const occlusion = (version) => ({ version, hidesSphere: (x, y, z, r) => (asked.push(r), y > 100) });
    batch.updateLod([0, 0, 0], distances, null, viewAlong([0, 1, 0]), occlusion(1));
    assert.deepEqual(batch.counts, { 4: 1, 3: 0, 2: 0, culled: 0, coarse: 0, occluded: 2 });
    assert.deepEqual(lod4Records(batch), [0]);
    // Each asked about with the scope's doubled half diagonal, as the view test.
    assert.ok(asked.every((r) => Math.abs(r - Math.hypot(1, 2, 0.1)) < 1e-3), `radii ${asked}`);
    const counts = batch.counts;
    batch.updateLod([0, 0, 0], distances, null, viewAlong([0, 1, 0]), occlusion(1));
    assert.equal(batch.counts, counts, 'the same image keeps the lists');
    batch.updateLod([0, 0, 0], distances, null, viewAlong([0, 1, 0]), { version: 2, hidesSphere: () => false });
    assert.deepEqual(batch.counts, { 4: 1, 3: 1, 2: 1, culled: 0, coarse: 0, occluded: 0 });
    // Turned off, the lists are sorted without it.
    batch.updateLod([0, 0, 0], distances, null, viewAlong([0, 1, 0]), occlusion(3));
    batch.updateLod([0, 0, 0], distances, null, viewAlong([0, 1, 0]));
    assert.equal(batch.counts.occluded, 0);
});

test('a sort that leaves a list as it was uploads nothing of it again', () => {
    const batch = new TerminalBatch(setOf([[0, 20, 0], [0, 150, 0], [0, 250, 0], [0, 260, 0]]), library, material, impostors);
    const run = batch.runs[0];
    const versions = () => [run.lod4.instanceMatrix.version, run.lod3.geometry.attributes.quadX.version, run.lod2.geometry.attributes.quadX.version];
    const hideBeyond = (version, y) => ({ version, hidesSphere: (x, sy) => sy > y });
    batch.updateLod([0, 0, 0], distances, null, null, hideBeyond(1, 1000));
    const first = versions();
    // A new image that hides nothing more: every list the same, nothing uploaded.
    batch.updateLod([0, 0, 0], distances, null, null, hideBeyond(2, 1000));
    assert.deepEqual(versions(), first);
    assert.deepEqual(batch.counts, { 4: 1, 3: 1, 2: 2, culled: 0, coarse: 0, occluded: 0 });
    // One that hides the farthest LOD2 terminal: the LOD2 list only shrinks, so its first slot
    // holds what it held; hiding the nearer one changes the slot, and only that list is uploaded.
    batch.updateLod([0, 0, 0], distances, null, null, hideBeyond(3, 255));
    assert.deepEqual(versions(), first);
    assert.equal(run.lod2.count, 1);
    batch.updateLod([0, 0, 0], distances, null, null, { version: 4, hidesSphere: (x, y) => y > 200 && y < 255 });
    const [lod4, lod3, lod2] = versions();
    assert.deepEqual([lod4, lod3], first.slice(0, 2));
    assert.ok(lod2 > first[2], 'the changed LOD2 list is uploaded');
    assert.deepEqual(Array.from(run.slots[2].subarray(0, run.lod2.count)), [3]);
    // Its matrix is record 3's: the corner at (0, 260, 0).
    assert.deepEqual(Array.from(run.lod2.instanceMatrix.array.subarray(12, 15)), [0, 260, 0]);
});

test('a sorted batch\'s instance buffers grow with what its lists draw', () => {
    // 300 terminals: 10 within LOD3's distance, 290 beyond it.
    const corners = [];
    for (let i = 0; i < 10; ++i) corners.push([i, 20, 0]);
    for (let i = 0; i < 290; ++i) corners.push([i, 150, 0]);
    const batch = new TerminalBatch(setOf(corners), library, material, impostors);
    const run = batch.runs[0];
    assert.equal(run.lod4.bytes, 0, 'nothing held before the first sort');
    batch.updateLod([0, 0, 0], distances);
    assert.equal(run.lod4.count, 10);
    assert.equal(run.lod4.bytes, 64 * 64, 'the first 64 instances, not the 300 of the run');
    const before = batch.gpuBytes;
    // With LOD3 ten times farther out (a taller viewport, the camera where it was) every
    // terminal is LOD4: the lists are sorted again, and the buffer grows to hold them all,
    // the matrices written before kept.
    batch.updateLod([0, 0, 0], { lod3: 1000, lod2: 2000 });
    assert.equal(run.lod4.count, 300);
    assert.equal(run.lod4.bytes, 300 * 64, 'no more than the run holds');
    assert.equal(batch.gpuBytes - before, (300 - 64) * (64 + 4), 'the growth of the instances and their records is counted');
    assert.equal(run.slots[4].length, 300, 'the LOD4 records grew with the list');
    assert.ok(run.slots[2].length < 300 && run.slots[3].length + run.slots[2].length >= 290, 'the impostor lists hold records for what they drew');
    for (const slot of [0, 9, 10, 299]) {
        const record = run.slots[4][slot];
        assert.deepEqual(Array.from(run.lod4.instanceMatrix.array.subarray(16 * slot + 12, 16 * slot + 15)), corners[record],
            `slot ${slot} holds record ${record}'s matrix`);
    }
    // A batch that is never sorted holds every terminal from the start.
    const plain = new TerminalBatch(setOf(corners.slice(0, 100)), library, material, null);
    assert.equal(plain.runs[0].lod4.count, 100);
    assert.equal(plain.gpuBytes, 100 * (64 + 4), 'its instances and building ids');
    assert.deepEqual(Array.from(plain.runs[0].lod4.instanceMatrix.array.subarray(16 * 99 + 12, 16 * 99 + 15)), corners[99]);
});

test('instance matrices are T·R·S of the records, which the batch does not keep', () => {
    const corners = [[1, 2, 3], [4, 5, 6]];
    for (const batch of [new TerminalBatch(setOf(corners), library, material, impostors), new TerminalBatch(setOf(corners), library, material, null)]) {
        batch.updateLod([0, 0, -50], { lod3: 1000, lod2: 2000 });
        const run = batch.runs[0];
        assert.equal(run.lod4.count, 2);
        for (let slot = 0; slot < 2; ++slot) {
            const record = batch.recordOf(run.lod4, slot);
            // X = +x scaled by w = 1, Y = +z by h = 2, Z = -y by the depth 0.1 * min(w, h).
            const expected = [1, 0, 0, 0, 0, 0, 2, 0, 0, -0.1, 0, 0, ...corners[record], 1];
            const m = run.lod4.instanceMatrix.array.subarray(16 * slot, 16 * slot + 16);
            expected.forEach((x, j) => assert.ok(Math.abs(m[j] - x) < 1e-4, `record ${record}, element ${j}: ${m[j]} against ${x}`));
        }
        assert.deepEqual(Array.from(batch.buildings), [0, 1]);
        assert.deepEqual(Object.keys(batch.set).sort(), ['cell', 'count', 'grammar'], 'no records kept');
    }
});
