// The viewer's impostor view conventions against impostor/src/view_layout.cpp: every view's
// direction and frame, continuous grid positions and tile origins, for grids of 8 and 5, as
// web_golden_payloads wrote them with the C++ ViewLayout; the LOD3 blend's weights.
import assert from 'node:assert/strict';
import test from 'node:test';

import { atlasTexel, blendViews, gridPosition, viewBasis, viewDirection } from '../src/render/impostor_views.js';
import { goldenJson } from './golden.js';

const near = (a, b, what) => a.forEach((v, i) => assert.ok(Math.abs(v - b[i]) < 1e-6, `${what}: ${a} against ${b}`));

test('view directions, frames and grid positions match the C++ layout', () => {
    for (const layout of goldenJson('view_layout.json')) {
        layout.views.forEach((view, i) => {
            const d = viewDirection(i, layout.grid);
            near(d, view.direction, `grid ${layout.grid} view ${i} direction`);
            const basis = viewBasis(d);
            near(basis.right, view.right, `view ${i} right`);
            near(basis.up, view.up, `view ${i} up`);
            const texel = atlasTexel(i, [-1, 1], layout);
            assert.deepEqual(texel, [view.tile[0] + layout.padding, view.tile[1] + layout.padding]);
            near(gridPosition(d, layout.grid), [i % layout.grid, Math.floor(i / layout.grid)], `view ${i} grid position`);
        });
        for (const probe of layout.grid_positions) near(gridPosition(probe.direction, layout.grid), probe.grid_position, 'probe');
    }
});

test('the LOD3 blend: weights sum to 1, an exact view gets all of it', () => {
    for (const grid of [5, 8]) {
        for (let i = 0; i < grid * grid; ++i) {
            const { views, weights } = blendViews(viewDirection(i, grid), grid);
            const k = views.indexOf(i);
            assert.ok(k >= 0 && Math.abs(weights[k] - 1) < 1e-6, `grid ${grid} view ${i}: ${views} ${weights}`);
        }
        const { weights } = blendViews([0.3, -0.2, 0.93], grid);
        assert.ok(Math.abs(weights.reduce((a, b) => a + b) - 1) < 1e-12);
        assert.ok(weights.every((w) => w >= 0));
    }
});
