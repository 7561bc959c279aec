// Far buildings as points end to end (part of ctest web.browser): `hexlod serve` on blocks of
// houses of its own in chromium, seen from 2.7 km, where each house is a few pixels across. The
// same view is drawn with far batches as points (the default) and with their shells (?points=0),
// and once more with the points hidden: the points must stand for every batch, draw far fewer
// triangles, cover about the pixels the shells cover and look much closer to them than nothing.
// Screenshots go to $HEXLOD_WEB_ARTIFACTS.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import test from 'node:test';

import { artifactsDir as artifacts, housesScene, imageDifference, settledView, statsShowing, withServedScene } from './harness.mjs';

const width = 640, height = 360;

// Low houses, so that a batch's largest box (about 24 m across) is under the point size from
// 1.9 km at this viewport.
const scene = housesScene({ name: 'points-test', seed: 5, cellSize: 80, count: 600, floors: [2, 3] });

// The box of every cell, world x and y, and its lowest ground.
async function cityBounds(page) {
    return page.evaluate(() => {
        const cells = window.hexlod.streamer.cells;
        const lo = [0, 1].map((a) => Math.min(...cells.map((c) => c.bounds.min[a])));
        const hi = [0, 1].map((a) => Math.max(...cells.map((c) => c.bounds.max[a])));
        return { lo, hi, ground: Math.min(...cells.map((c) => c.origin[2])) };
    });
}

// The canvas as a PNG with every point object hidden for one frame, drawn by hand.
async function withoutPoints(page) {
    const png = await page.evaluate(() => {
        const { world } = window.hexlod;
        const points = [];
        world.scene.traverse((o) => o.isPoints && o.visible && points.push(o));
        points.forEach((o) => (o.visible = false));
        world.renderer.render(world.scene, world.camera);
        const url = document.getElementById('view').toDataURL('image/png');
        points.forEach((o) => (o.visible = true));
        return url;
    });
    return Buffer.from(png.split(',')[1], 'base64');
}

test('far batches are points that stand for their buildings', { timeout: 240000 }, async () => {
    await withServedScene(scene, { impostorGrid: 4, viewport: { width, height } }, async ({ base, page, pageErrors }) => {
        // three.js reports a shader that does not compile, or a geometry it cannot bound, on the
        // console (the browser's request for a favicon, which the service has not, is no error).
        const consoleErrors = [];
        page.on('console', (m) => m.type() === 'error' && !m.location().url.endsWith('/favicon.ico') && consoleErrors.push(m.text()));
        await settledView(page, `${base}?aa=0&points=0`); // the opening view loads the index
        const city = await cityBounds(page);
        // 2.4 km south of the city's middle and 1.2 km up, looking at it.
        const centre = [0, 1].map((a) => 0.5 * (city.lo[a] + city.hi[a]));
        const up = 1200, back = 2400;
        const pitch = (-Math.atan2(up, back) * 180) / Math.PI;
        const camera = `camera=${centre[0]},${centre[1] - back},${city.ground + up},90,${pitch}`;
        const points = await settledView(page, `${base}?aa=0&${camera}`);
        const stats = await statsShowing(page, `; ${points.state.streamer.pointBatches} far batches as points`);
        const hidden = await withoutPoints(page);
        const shells = await settledView(page, `${base}?aa=0&${camera}&points=0`);
        fs.writeFileSync(path.join(artifacts, 'points-on.png'), points.image);
        fs.writeFileSync(path.join(artifacts, 'points-off.png'), shells.image);
        fs.writeFileSync(path.join(artifacts, 'points-hidden.png'), hidden);
        assert.deepEqual(pageErrors, []);
        assert.deepEqual(consoleErrors, []);

        const extruded = points.state.streamer.cells.extruded;
        assert.ok(extruded > 0, `cells ${JSON.stringify(points.state.streamer.cells)}`);
        assert.ok(points.state.streamer.pointBatches >= extruded, `${points.state.streamer.pointBatches} batches as points of ${extruded} cells`);
        assert.match(stats, new RegExp(`; ${points.state.streamer.pointBatches} far batches as points`), 'the stats panel says so');
        assert.equal(shells.state.streamer.pointBatches, 0);
        assert.ok(points.state.triangles < 0.5 * shells.state.triangles, `triangles ${points.state.triangles} against ${shells.state.triangles}`);

        // The buildings' pixels: where the shells, or the points, change the image without them.
        const shellPixels = (await imageDifference(page, shells.image, hidden)).different;
        const pointPixels = (await imageDifference(page, points.image, hidden)).different;
        assert.ok(shellPixels > 300, `the shells cover ${shellPixels} pixels`);
        const coverage = pointPixels / shellPixels;
        const against = await imageDifference(page, points.image, shells.image);
        const nothing = await imageDifference(page, hidden, shells.image);
        console.log(`points: ${points.state.streamer.pointBatches} batches, ${points.state.triangles} triangles against ${shells.state.triangles}; ` +
            `cover ${coverage.toFixed(2)} of the shells' ${shellPixels} pixels; ${against.psnr.toFixed(1)} dB from the shells, nothing ${nothing.psnr.toFixed(1)} dB`);
        assert.ok(coverage > 0.6 && coverage < 1.6, `the points cover ${coverage.toFixed(2)} of the shells' pixels`);
        assert.ok(against.psnr > nothing.psnr + 4, `PSNR against the shells: points ${against.psnr.toFixed(2)} dB, nothing ${nothing.psnr.toFixed(2)} dB`);
    });
});
