// The viewer's impostor view conventions against impostor/src/view_layout.cpp: every view's
// direction and frame, continuous grid positions and tile origins, for grids of 8 and 5 on the
// facades' hemisphere and the trees' full sphere, as web_golden_payloads wrote them with the C++
// ViewLayout; the blend's weights on both.
import assert from 'node:assert/strict';
import test from 'node:test';

import {
    atlasTexel,
    blendViews,
    decodeOctahedral,
    encodeOctahedral,
    FULL_SPHERE,
    gridPosition,
    HEMISPHERE,
    viewBasis,
    viewDirection,
} from '../src/render/impostor_views.js';
import { goldenJson } from './golden.js';

const near = (a, b, what) => a.forEach((v, i) => assert.ok(Math.abs(v - b[i]) < 1e-6, `${what}: ${a} against ${b}`));

test('view directions, frames and grid positions match the C++ layout', () => {
    const layouts = goldenJson('view_layout.json');
    assert.deepEqual([...new Set(layouts.map((l) => l.sphere))], [HEMISPHERE, FULL_SPHERE]);
    for (const layout of layouts) {
        const { grid, sphere } = layout;
        layout.views.forEach((view, i) => {
            const d = viewDirection(i, grid, sphere);
            near(d, view.direction, `${sphere} grid ${grid} view ${i} direction`);
            const basis = viewBasis(d, sphere);
            near(basis.right, view.right, `view ${i} right`);
            near(basis.up, view.up, `view ${i} up`);
            const texel = atlasTexel(i, [-1, 1], layout);
            assert.deepEqual(texel, [view.tile[0] + layout.padding, view.tile[1] + layout.padding]);
            near(gridPosition(d, grid, sphere), [i % grid, Math.floor(i / grid)], `view ${i} grid position`);
        });
        for (const probe of layout.grid_positions)
            near(gridPosition(probe.direction, grid, sphere), probe.grid_position, `${sphere} probe ${probe.direction}`);
    }
});

test('the blend: weights sum to 1, an exact view gets all of it', () => {
    for (const sphere of [HEMISPHERE, FULL_SPHERE]) {
        for (const grid of [5, 8]) {
            for (let i = 0; i < grid * grid; ++i) {
                const { views, weights } = blendViews(viewDirection(i, grid, sphere), grid, sphere);
                const k = views.indexOf(i);
                assert.ok(k >= 0 && Math.abs(weights[k] - 1) < 1e-6, `${sphere} grid ${grid} view ${i}: ${views} ${weights}`);
            }
            // Below the horizon and straight down too, where the full sphere folds its corners.
            for (const d of [[0.3, -0.2, 0.93], [0.4, 0.1, -0.9], [0, 0, -1], [-1, 0, 0]]) {
                const { views, weights } = blendViews(d, grid, sphere);
                assert.ok(Math.abs(weights.reduce((a, b) => a + b) - 1) < 1e-12, `${sphere} ${d}: ${weights}`);
                assert.ok(weights.every((w) => w >= 0));
                assert.ok(views.every((v) => v >= 0 && v < grid * grid));
            }
        }
    }
});

test('the octahedral map round-trips every direction, the lower half included', () => {
    for (let i = 0; i < 200; ++i) {
        const z = -1 + (2 * (i + 0.5)) / 200, phi = i * 2.399963;
        const r = Math.sqrt(1 - z * z), d = [r * Math.cos(phi), r * Math.sin(phi), z];
        const p = encodeOctahedral(d);
        assert.ok(Math.abs(p[0]) <= 1 + 1e-12 && Math.abs(p[1]) <= 1 + 1e-12);
        near(decodeOctahedral(p[0], p[1]), d, `direction ${d}`);
    }
});
