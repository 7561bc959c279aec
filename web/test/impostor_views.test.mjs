// The viewer's impostor view conventions against impostor/src/view_layout.cpp: every view's
// direction and frame and tile origin, for grids of 8 and 5 on the facades' hemisphere and the
// trees' full sphere, as web_golden_payloads wrote them with the C++ ViewLayout.
import assert from 'node:assert/strict';
import test from 'node:test';

import { atlasTexel, FULL_SPHERE, HEMISPHERE, viewBasis, viewDirection } from '../src/render/impostor_views.js';
import { goldenJson } from './golden.js';

const near = (a, b, what) => a.forEach((v, i) => assert.ok(Math.abs(v - b[i]) < 1e-6, `${what}: ${a} against ${b}`));

test('view directions, frames and tiles match the C++ layout', () => {
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
        });
    }
});
