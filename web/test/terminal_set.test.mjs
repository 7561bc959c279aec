// The JavaScript terminal-set decoder against the C++ codec: the golden bytes of
// tests/grammar/terminal_set_codec_test.cpp, real residential and business batches encoded in
// C++ (every record compared with the C++ decoder's unpackTerminal), and the C++ decoder's
// rejections: every truncation, trailing bytes, bit flips, foreign and lying headers.
import assert from 'node:assert/strict';
import test from 'node:test';

import { decodeTerminalSet } from '../src/payload/terminal_set.js';
import { PayloadError } from '../src/payload/payload_error.js';
import { quaternionAxes, unpackRecord } from '../src/payload/record.js';
import { cppGoldenBytes, goldenPayload } from './golden.js';

const close = (a, b, tolerance, what) =>
    assert.ok(Math.abs(a - b) <= tolerance, `${what}: ${a} against ${b}`);

test('the golden bytes decode to the hand-built set of the C++ test', () => {
    const set = decodeTerminalSet(cppGoldenBytes('terminal_set_codec_test.cpp'));
    assert.equal(set.checksum, 'd5e045f59fabde52');
    assert.deepEqual(set.cell, { q: -3, r: 5 });
    assert.equal(set.grammar, 2);
    assert.equal(set.grammarHash, '1122334455667788');
    assert.equal(set.key, '99aabbccddeeff00');
    assert.deepEqual(set.origin, [1000.5, -250.25, 12]);
    assert.deepEqual([...set.countPerShape], [2, 1]);
    assert.deepEqual(
        [...set.records],
        [
            0x3f800000, 0x40000000, 0x40400000, 10, 0x00007fff, 0x7fff0000, 0x40003c00, 0,
            0x3fc00000, 0x40000000, 0x40c00000, 10, 0x00007fff, 0x7fff0000, 0x40003c00, 0,
            0xc0800000, 0x3f000000, 0x40400000, 11, 0x5a825a82, 0, 0x3c003800, 0x38000001,
        ],
    );
    const r = unpackRecord(set, 2);
    assert.deepEqual(r.position, [-4, 0.5, 3]);
    assert.equal(r.building, 11);
    assert.equal(r.shape, 1);
    assert.deepEqual(r.size, [0.5, 1]);
    assert.equal(r.depthRatio, 0.5);
});

for (const name of ['residential', 'business']) {
    test(`a real ${name} batch decodes as the C++ decoder reads it`, () => {
        const { bytes, expected } = goldenPayload(`${name}.hxt`);
        const set = decodeTerminalSet(bytes);
        assert.equal(set.checksum, expected.checksum);
        assert.deepEqual([set.cell.q, set.cell.r], expected.cell);
        assert.equal(set.key, expected.key);
        assert.equal(set.grammarHash, expected.grammar_hash);
        assert.deepEqual(set.origin, expected.origin);
        assert.deepEqual([...set.countPerShape], expected.count_per_shape);
        assert.equal(set.count, expected.records.length);
        assert.ok(set.count > 1000, `${set.count} records`);
        const axes = new Float64Array(9);
        expected.records.forEach((e, i) => {
            const r = unpackRecord(set, i);
            assert.deepEqual(r.position, e.position.map(Math.fround), `record ${i} position`);
            assert.equal(r.building, e.building);
            assert.equal(r.shape, e.shape);
            assert.deepEqual(r.size, e.size);
            assert.equal(r.depthRatio, e.depth_ratio);
            quaternionAxes(r.quaternion, axes);
            for (let k = 0; k < 3; ++k) {
                close(axes[k], e.axis_x[k], 1e-6, `record ${i} axis x`);
                close(axes[3 + k], e.axis_y[k], 1e-6, `record ${i} axis y`);
                close(axes[6 + k], e.normal[k], 1e-6, `record ${i} normal`);
            }
        });
    });
}

function rejects(bytes, pattern) {
    assert.throws(() => decodeTerminalSet(bytes), (e) => e instanceof PayloadError && pattern.test(e.message));
}

test('every truncation and trailing bytes are rejected with a reason', () => {
    const good = cppGoldenBytes('terminal_set_codec_test.cpp');
    for (let n = 0; n < good.length; ++n) rejects(good.subarray(0, n), /truncated|not a zstd frame/);
    const longer = new Uint8Array(good.length + 1);
    longer.set(good);
    rejects(longer, /trailing bytes/);
});

test('a flipped bit is rejected or decodes to the same records, never to others', () => {
    const good = cppGoldenBytes('terminal_set_codec_test.cpp');
    const reference = decodeTerminalSet(good);
    let rejected = 0;
    for (let bit = 0; bit < 8 * good.length; ++bit) {
        const bad = good.slice();
        bad[bit >> 3] ^= 1 << (bit & 7);
        try {
            const set = decodeTerminalSet(bad);
            // Only bits zstd ignores may pass, and the checksum holds the content to the original.
            assert.deepEqual([...set.records], [...reference.records], `bit ${bit}`);
        } catch (e) {
            assert.ok(e instanceof PayloadError, `bit ${bit}: ${e}`);
            ++rejected;
        }
    }
    assert.ok(rejected > 0.9 * 8 * good.length, `${rejected} of ${8 * good.length} flips rejected`);
});

test('foreign input and lying headers are rejected with a reason', () => {
    const good = cppGoldenBytes('terminal_set_codec_test.cpp');
    const edit = (at, f) => {
        const bad = good.slice();
        f(new DataView(bad.buffer), at);
        return bad;
    };
    rejects(new TextEncoder().encode('<html>not a payload</html>' + ' '.repeat(100)), /bad magic/);
    rejects(edit(4, (v, at) => v.setUint32(at, 2, true)), /unsupported terminal set version 2/);
    rejects(edit(72, (v, at) => v.setUint32(at, 4, true)), /sum to 3, the header says 4/);
    rejects(edit(72, (v, at) => v.setUint32(at + 4, 1, true)), /exceeds the limit/);
    rejects(edit(88, (v, at) => v.setUint32(at, 70000, true)), /exceeds 65536/);
    rejects(edit(92, (v, at) => (v.setUint32(at, 1, true), v.setUint32(at + 4, 2, true))), /checksum mismatch|outside the run/);
    assert.throws(() => decodeTerminalSet('text'), PayloadError);
});
