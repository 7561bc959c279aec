// LOD0's base volumes (src/render/extruded_mesh.js): a footprint's prism as an indexed triangle
// list, walls facing out and the roof up, each triangle naming its building, in the compact
// attributes the cache counts.
import assert from 'node:assert/strict';
import test from 'node:test';

import { buildExtrudedGeometry } from '../src/render/extruded_mesh.js';
import { geometryBytes } from '../src/render/geometry_bytes.js';

// A 10 x 6 m rectangle (counter-clockwise) 8 m tall on a base at 2 m, building id 42, and a
// two-vertex footprint, which has no volume.
function extrudedSet() {
    return {
        parametersPerBuilding: 1,
        parameters: [Float32Array.of(3.5, 3.5)],
        buildings: {
            count: 2, id: Uint32Array.of(42, 43), firstVertex: Uint32Array.of(0, 4), vertexCount: Uint32Array.of(4, 2),
            height: Float32Array.of(8, 5), baseElevation: Float32Array.of(2, 0), wallMaterial: Uint32Array.of(3, 0),
        },
        footprints: { x: Float32Array.of(0, 10, 10, 0, 0, 1), y: Float32Array.of(0, 0, 6, 6, 0, 0) },
    };
}
const grammar = { parameters: [{ name: 'floor_h' }] };

function vertex(geometry, v) {
    const p = geometry.attributes.position.array, n = geometry.attributes.normal.array;
    return { p: [p[3 * v], p[3 * v + 1], p[3 * v + 2]], n: [n[3 * v] / 127, n[3 * v + 1] / 127, n[3 * v + 2] / 127] };
}

test('a prism: four walls of two triangles facing out, a roof of two facing up', () => {
    const { geometry, buildingOfTriangle } = buildExtrudedGeometry(extrudedSet(), grammar);
    const index = geometry.index.array;
    assert.equal(geometry.attributes.position.count, 4 * 4 + 4, 'a quad per wall, the ring for the roof');
    assert.equal(index.length, 3 * (4 * 2 + 2));
    assert.deepEqual(Array.from(buildingOfTriangle), new Array(10).fill(42));
    for (let t = 0; t < index.length / 3; ++t) {
        const [a, b, c] = [0, 1, 2].map((k) => vertex(geometry, index[3 * t + k]));
        const u = a.p.map((x, i) => b.p[i] - x), w = a.p.map((x, i) => c.p[i] - x);
        const cross = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
        const facing = cross[0] * a.n[0] + cross[1] * a.n[1] + cross[2] * a.n[2];
        assert.ok(facing > 0, `triangle ${t} winds counter-clockwise seen from where its normal points`);
        const centre = [0, 1].map((i) => (a.p[i] + b.p[i] + c.p[i]) / 3);
        const outward = (centre[0] - 5) * a.n[0] + (centre[1] - 3) * a.n[1];
        if (a.n[2] > 0.5) assert.ok([a, b, c].every((v) => v.p[2] === 10), 'the roof at base + height');
        else assert.ok(outward > 0, `wall triangle ${t} faces out of the footprint`);
    }
    const area = (zUp) => {
        let sum = 0;
        for (let t = 0; t < index.length / 3; ++t) {
            const [a, b, c] = [0, 1, 2].map((k) => vertex(geometry, index[3 * t + k]));
            if ((a.n[2] > 0.5) !== zUp) continue;
            const u = a.p.map((x, i) => b.p[i] - x), w = a.p.map((x, i) => c.p[i] - x);
            sum += 0.5 * Math.hypot(u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]);
        }
        return sum;
    };
    assert.ok(Math.abs(area(true) - 60) < 1e-4, 'the roof covers the footprint');
    assert.ok(Math.abs(area(false) - 32 * 8) < 1e-4, 'the walls cover the perimeter times the height');
});

test('walls carry the window grid and their length along the facade; compact attributes', () => {
    const { geometry } = buildExtrudedGeometry(extrudedSet(), grammar);
    const { facade, windowGrid, color, normal } = geometry.attributes;
    assert.deepEqual(Array.from(windowGrid.array.subarray(0, 2)), [3.5, 3]); // floor_h, no bay column
    assert.deepEqual(Array.from(facade.array.subarray(3 * 4, 3 * 8)), [10, 0, 1, 16, 0, 1, 16, 8, 1, 10, 8, 1]); // 2nd wall
    assert.equal(normal.array.BYTES_PER_ELEMENT, 1);
    assert.ok(normal.normalized && color.normalized);
    assert.equal(color.array.BYTES_PER_ELEMENT, 2);
    assert.equal(geometryBytes(geometry), 20 * 41 + 30 * 2);
    const dark = buildExtrudedGeometry(extrudedSet(), grammar, { windows: false, inset: 0.5 }).geometry;
    assert.ok(dark.attributes.facade.array.every((x, i) => i % 3 !== 2 || x === 0), 'backing walls have no windows');
    assert.ok(dark.attributes.position.array.every((x, i) => i % 3 !== 0 || (x >= 0.5 - 1e-6 && x <= 9.5 + 1e-6)), 'inset');
});
