// The impostor shaders in chromium (part of ctest web.browser): impostor_page.js bundled with
// esbuild and loaded into a page. LOD2 must show exactly the central view (5: red 80, green 175
// in sRGB) on the rectangle of the mesh's bounds on the wall plane, and nothing beyond it; LOD3
// from straight in front must blend the four views around the front direction (5, 6, 9, 10,
// weights 0.22 to 0.28 from the table's texel beside the centre: red near their mean, 120);
// both must cover the quad's middle. Lit by the viewer's lights, LOD2 must shade as a Lambert
// mesh of its albedo facing the same way.
import assert from 'node:assert/strict';
import path from 'node:path';
import test from 'node:test';
import { fileURLToPath } from 'node:url';

import * as esbuild from 'esbuild';

import { launchChromium } from './harness.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));

test('LOD2 and LOD3 impostor shaders compile and sample the right views', { timeout: 120000 }, async () => {
    const bundle = await esbuild.build({ entryPoints: [path.join(here, 'impostor_page.js')], bundle: true, format: 'esm', write: false, logLevel: 'warning' });
    const script = bundle.outputFiles[0].text.replaceAll('</script>', '<\\/script>');
    const browser = await launchChromium({ width: 200, height: 200 });
    try {
        const errors = [];
        browser.page.on('pageerror', (e) => errors.push(e.message));
        await browser.page.setContent(`<!doctype html><html><body><script type="module">${script}</script></body></html>`);
        await browser.page.waitForFunction(() => window.impostorResult, null, { timeout: 60000 });
        const { results, errors: shaderErrors } = await browser.page.evaluate(() => window.impostorResult);
        assert.deepEqual([...errors, ...shaderErrors], []);
        // LOD3's quad spans the bounding sphere; LOD2's only the mesh bounds' rectangle on the wall.
        assert.ok(results[3].covered > 800, `LOD3 covers ${results[3].covered} pixels`);
        const wall = results.wallRectangle;
        assert.ok(Math.abs(results[2].covered - wall) < 0.05 * wall, `LOD2 covers ${results[2].covered} pixels, its rectangle ${wall.toFixed(0)}`);
        const [r2, g2] = results[2].centre;
        assert.ok(Math.abs(r2 - 80) <= 2 && Math.abs(g2 - 175) <= 2, `LOD2 centre ${results[2].centre}`);
        const [r3] = results[3].centre;
        assert.ok(r3 > 100 && r3 < 140, `LOD3 centre ${results[3].centre}`);
        // Under the viewer's lights an impostor shades as its mesh does, whichever way it faces.
        for (const [facing, { impostor, mesh }] of Object.entries(results.lighting)) {
            const apart = Math.max(...impostor.map((c, i) => Math.abs(c - mesh[i])));
            assert.ok(apart <= 2, `facing ${facing}: impostor ${impostor}, mesh ${mesh}`);
        }
        const { north, south } = results.lighting;
        assert.ok(south.mesh[0] > north.mesh[0], `the sun lights the south facade (${south.mesh}) over the north (${north.mesh})`);
    } finally {
        await browser.close();
    }
});
