// The JavaScript extruded-set decoder against the C++ codec: the golden bytes of
// tests/grammar/extruded_set_codec_test.cpp, real batches encoded in C++ compared building by
// building and element by element, and the C++ decoder's rejections.
import assert from 'node:assert/strict';
import test from 'node:test';

import { decodeExtrudedSet } from '../src/payload/extruded_set.js';
import { PayloadError } from '../src/payload/payload_error.js';
import { cppGoldenBytes, goldenPayload } from './golden.js';

test('the golden bytes decode to the hand-built set of the C++ test', () => {
    const set = decodeExtrudedSet(cppGoldenBytes('extruded_set_codec_test.cpp'));
    assert.equal(set.checksum, '1cd1dceaa9226c8c');
    assert.deepEqual(set.cell, { q: -3, r: 5 });
    assert.equal(set.key, '99aabbccddeeff00');
    assert.deepEqual(set.origin, [1000.5, -250.25, 12]);
    assert.deepEqual([...set.buildings.id], [10, 11]);
    assert.deepEqual([...set.buildings.vertexCount], [3, 4]);
    assert.deepEqual([...set.buildings.firstElement], [0, 1]);
    assert.deepEqual([...set.buildings.baseElevation], [0, 0.5]);
    assert.deepEqual([...set.buildings.height], [9, 6]);
    assert.deepEqual([...set.buildings.wallMaterial], [2, 0]);
    assert.deepEqual([...set.footprints.x], [0, 4, 0, 10, 12, 12, 10]);
    assert.deepEqual([...set.footprints.y], [0, 0, 3, 10, 10, 12, 12]);
    assert.deepEqual([...set.elements.origin[0]], [0, 10, 12]);
    assert.deepEqual([...set.elements.axisX[1]], [0, 0, 1]);
    assert.deepEqual([...set.elements.size[1]], [9, 6, 6]);
    assert.deepEqual([...set.elements.atom], [0, 0, 1]);
    assert.deepEqual(set.parameters.map((c) => [...c]), [[3, Math.fround(3.2)], [2.5, 2.5]]);
});

test('without its facade frames a set keeps everything else, and counts only what it keeps', () => {
    const bytes = goldenPayload('business.hxe').bytes;
    const whole = decodeExtrudedSet(bytes), lean = decodeExtrudedSet(bytes, { elements: false });
    assert.ok(whole.elements.count > 0);
    assert.deepEqual(lean.elements, { count: whole.elements.count });
    for (const column of ['id', 'vertexCount', 'firstElement', 'baseElevation', 'height', 'wallMaterial'])
        assert.deepEqual([...lean.buildings[column]], [...whole.buildings[column]], column);
    assert.deepEqual([...lean.footprints.x], [...whole.footprints.x]);
    assert.deepEqual(lean.parameters.map((c) => [...c]), whole.parameters.map((c) => [...c]), 'the columns after the frames');
    assert.equal(lean.byteSize, whole.byteSize - 52 * whole.elements.count);
});

for (const name of ['residential', 'business']) {
    test(`a real ${name} batch decodes as the C++ decoder reads it`, () => {
        const { bytes, expected } = goldenPayload(`${name}.hxe`);
        const set = decodeExtrudedSet(bytes);
        assert.equal(set.key, expected.key);
        assert.deepEqual(set.origin, expected.origin);
        assert.equal(set.buildings.count, expected.buildings.length);
        expected.buildings.forEach((e, i) => {
            const b = set.buildings;
            assert.equal(b.id[i], e.id);
            assert.equal(b.baseElevation[i], Math.fround(e.base_elevation));
            assert.equal(b.height[i], Math.fround(e.height));
            assert.equal(b.wallMaterial[i], e.wall_material);
            assert.equal(b.elementCount[i], e.element_count);
            const ring = [];
            for (let k = 0; k < b.vertexCount[i]; ++k) ring.push([set.footprints.x[b.firstVertex[i] + k], set.footprints.y[b.firstVertex[i] + k]]);
            assert.deepEqual(ring, e.footprint.map((p) => p.map(Math.fround)));
            assert.deepEqual(set.parameters.map((column) => column[i]), e.parameters.map(Math.fround));
        });
        assert.equal(set.elements.count, expected.elements.length);
        expected.elements.forEach((e, i) => {
            const el = set.elements;
            for (let k = 0; k < 3; ++k) {
                assert.equal(el.origin[k][i], Math.fround(e.origin[k]));
                assert.equal(el.axisX[k][i], Math.fround(e.axis_x[k]));
                assert.equal(el.axisY[k][i], Math.fround(e.axis_y[k]));
            }
            assert.deepEqual([el.size[0][i], el.size[1][i]], e.size.map(Math.fround));
            assert.equal(el.rule[i], e.rule);
            assert.equal(el.atom[i], e.atom);
        });
    });
}

test('truncations, trailing bytes, bit flips and lying headers are rejected with a reason', () => {
    const good = cppGoldenBytes('extruded_set_codec_test.cpp');
    const rejects = (bytes, pattern) =>
        assert.throws(() => decodeExtrudedSet(bytes), (e) => e instanceof PayloadError && pattern.test(e.message));
    for (let n = 0; n < good.length; ++n) rejects(good.subarray(0, n), /truncated|not a zstd frame/);
    const longer = new Uint8Array(good.length + 3);
    longer.set(good);
    rejects(longer, /trailing bytes/);
    const edit = (at, value) => {
        const bad = good.slice();
        new DataView(bad.buffer).setUint32(at, value, true);
        return bad;
    };
    rejects(edit(0, 0x31545848), /bad magic/); // a terminal set's magic
    rejects(edit(4, 9), /unsupported extruded set version 9/);
    rejects(edit(84, 1), /reserved header word/);
    rejects(edit(72, 1 << 25), /limits/);
    rejects(edit(28, 5000), /limits/);
    rejects(edit(72, 3), /declares|decodes to/);
    const reference = decodeExtrudedSet(good);
    for (let bit = 0; bit < 8 * good.length; ++bit) {
        const bad = good.slice();
        bad[bit >> 3] ^= 1 << (bit & 7);
        try {
            const set = decodeExtrudedSet(bad);
            assert.deepEqual([...set.buildings.height], [...reference.buildings.height], `bit ${bit}`);
            assert.deepEqual([...set.footprints.x], [...reference.footprints.x], `bit ${bit}`);
        } catch (e) {
            assert.ok(e instanceof PayloadError, `bit ${bit}: ${e}`);
        }
    }
});
