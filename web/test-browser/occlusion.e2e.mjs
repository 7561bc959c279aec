// Occlusion culling end to end (part of ctest web.browser): `hexlod serve` on blocks of houses
// of its own in chromium, the camera at eye level south of them looking north. The same view
// is drawn with occlusion culling (?occlusion=1) and without (?occlusion=0): culling must
// leave out terminals, draw fewer impostor quads, and change next to no pixel (what it leaves
// out is behind the base volumes). Screenshots go to $HEXLOD_WEB_ARTIFACTS.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import test from 'node:test';

import { artifactsDir as artifacts, housesScene, imageDifference, settledView, withServedScene } from './harness.mjs';

const width = 640, height = 360;

// Rows of three-to-five-storey houses: at eye level the first row hides most of the rest.
const scene = housesScene({ name: 'occlusion-test', seed: 11, cellSize: 80, count: 48, floors: [3, 5] });

// Of every extruded set loaded, the building reaching farthest south: its footprint's bounds
// (world x, y) and its base.
async function southernmostBuilding(page) {
    return page.evaluate(() => {
        const h = window.hexlod;
        let best = null;
        for (const cell of h.streamer.cells)
            for (const batch of cell.batches) {
                if (!batch.shown.extruded) continue;
                const { buildings, footprints } = h.streamer.cache.get(batch.shown.extruded).set;
                for (let i = 0; i < buildings.count; ++i) {
                    const min = [Infinity, Infinity], max = [-Infinity, -Infinity];
                    for (let k = 0; k < buildings.vertexCount[i]; ++k) {
                        const v = buildings.firstVertex[i] + k;
                        const p = [footprints.x[v] + cell.origin[0], footprints.y[v] + cell.origin[1]];
                        for (let a = 0; a < 2; ++a) [min[a], max[a]] = [Math.min(min[a], p[a]), Math.max(max[a], p[a])];
                    }
                    if (!best || min[1] < best.min[1]) best = { min, max, base: buildings.baseElevation[i] + cell.origin[2] };
                }
            }
        return best;
    });
}

test('occlusion culling leaves out hidden terminals and changes no visible pixel', { timeout: 240000 }, async () => {
    await withServedScene(scene, { impostorGrid: 4, viewport: { width, height } }, async ({ base, page, pageErrors }) => {
        // Eye level, 15 m south of the southernmost house, looking north past its side (the
        // opening view, over the whole city, loads every extruded set).
        await settledView(page, `${base}?aa=0&occlusion=0`);
        const house = await southernmostBuilding(page);
        assert.ok(house, 'no building loaded');
        const camera = [house.max[0] - 2, house.min[1] - 15, house.base + 1.7].map((v) => v.toFixed(2)).join(',');
        const query = `?aa=0&mode=walk&camera=${camera},90,0`;
        const culled = await settledView(page, `${base}${query}&occlusion=1`);
        const kept = await settledView(page, `${base}${query}&occlusion=0`);
        const stats = await page.locator('#stats').textContent();
        fs.writeFileSync(path.join(artifacts, 'occlusion-on.png'), culled.image);
        fs.writeFileSync(path.join(artifacts, 'occlusion-off.png'), kept.image);
        assert.deepEqual(pageErrors, []);
        assert.match(culled.state.occlusion, /^occlusion on, \d+ hidden$/);
        assert.match(kept.state.occlusion, /^occlusion off$/);
        assert.match(stats, /occlusion off/, 'the stats panel says so');

        const [on, off] = [culled.state.streamer.terminals, kept.state.streamer.terminals];
        const drawn = (t) => t[4] + t[3] + t[2];
        assert.ok(on.occluded > 0, `nothing hidden: ${JSON.stringify(on)}`);
        assert.equal(off.occluded, 0);
        assert.ok(drawn(on) < drawn(off), `terminals drawn: ${JSON.stringify(on)} against ${JSON.stringify(off)}`);
        assert.ok(on.occluded <= drawn(off), 'only what would be drawn can be hidden');
        const { psnr, apart, different, pixels } = await imageDifference(page, culled.image, kept.image);
        console.log(`occlusion: ${on.occluded} of ${drawn(off)} terminals hidden; ${psnr.toFixed(1)} dB, ${different} of ${pixels} pixels differ, ${apart} by more than 24`);
        assert.ok(psnr > 40, `${psnr.toFixed(1)} dB between the views with and without culling`);
        assert.ok(apart < 0.001 * pixels, `${apart} pixels apart`);
    });
});
