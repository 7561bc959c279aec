// Far trees as points end to end (part of ctest web.browser): `hexlod serve` on parks of its
// own in chromium, seen from about 1.4 km, where each tree's sphere spans about two pixels. The
// same view is drawn with far trees as points (the default), as billboards (?treepoints=0) and
// without trees: the points must stand for the far trees, cover about the pixels the billboards
// cover and look closer to them than no trees, pixel for pixel and more so over blocks of 4 x 4
// pixels, where points and billboards in neighbouring pixels meet. The canvas is multisampled,
// as the viewer's default: the billboards' coverage is then their alpha, as the points' areas
// assume (with ?aa=0 the points take the share of texels a cutout at one half keeps, and cover
// about a fifth more than the billboards). Screenshots go to $HEXLOD_WEB_ARTIFACTS.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import test from 'node:test';

import { artifactsDir as artifacts, imageDifference, parkScene, settledView, statsShowing, withServedScene } from './harness.mjs';

const width = 640, height = 360;

const scene = parkScene({ name: 'tree-points-test', seed: 11, cellSize: 120, houses: 30, parkShare: 0.7, trees: 1500 });

test('far trees are points that stand for their billboards', { timeout: 300000 }, async () => {
    await withServedScene(scene, { impostorGrid: 4, viewport: { width, height } }, async ({ base, page, pageErrors }) => {
        const consoleErrors = [];
        page.on('console', (m) => m.type() === 'error' && !m.location().url.endsWith('/favicon.ico') && consoleErrors.push(m.text()));
        await settledView(page, base); // the opening view loads the index
        const city = await page.evaluate(() => {
            const cells = window.hexlod.streamer.cells;
            const lo = [0, 1].map((a) => Math.min(...cells.map((c) => c.bounds.min[a])));
            const hi = [0, 1].map((a) => Math.max(...cells.map((c) => c.bounds.max[a])));
            return { centre: [0, 1].map((a) => 0.5 * (lo[a] + hi[a])), ground: Math.min(...cells.map((c) => c.origin[2])) };
        });
        // 1.3 km south of the parks and 500 m up, looking at them.
        const up = 500, back = 1300;
        const pitch = (-Math.atan2(up, back) * 180) / Math.PI;
        const camera = `camera=${city.centre[0]},${city.centre[1] - back},${city.ground + up},90,${pitch}`;
        const points = await settledView(page, `${base}?${camera}`);
        const drawn = points.state.streamer.trees;
        const stats = await statsShowing(page, `, ${drawn.points} points, `);
        const billboards = await settledView(page, `${base}?${camera}&treepoints=0`);
        const none = await settledView(page, `${base}?${camera}&trees=none`);
        for (const [name, shot] of Object.entries({ points, billboards, none }))
            fs.writeFileSync(path.join(artifacts, `tree-points-${name}.png`), shot.image);
        assert.deepEqual(pageErrors, []);
        assert.deepEqual(consoleErrors, []);

        const boards = billboards.state.streamer.trees;
        assert.ok(drawn.points > 500, `trees ${JSON.stringify(drawn)}`);
        assert.match(stats, new RegExp(`trees: ${drawn.billboards} billboards( \\(\\d+ of them hidden\\))?, ${drawn.points} points, `), 'the stats panel says so');
        assert.equal(boards.points, 0, '?treepoints=0 draws none');
        assert.equal(drawn.points + drawn.billboards, boards.billboards, 'the same far trees, each in one form');
        assert.ok(points.state.triangles < billboards.state.triangles - 2 * 500, `triangles ${points.state.triangles} against ${billboards.state.triangles}`);

        // The trees' pixels: where the billboards, or the points, change the image without trees.
        const boardPixels = (await imageDifference(page, billboards.image, none.image)).different;
        const pointPixels = (await imageDifference(page, points.image, none.image)).different;
        assert.ok(boardPixels > 300, `the billboards cover ${boardPixels} pixels`);
        const coverage = pointPixels / boardPixels;
        const against = await imageDifference(page, points.image, billboards.image);
        const nothing = await imageDifference(page, none.image, billboards.image);
        console.log(`tree points: ${drawn.points} points, ${drawn.billboards} billboards, ${points.state.triangles} triangles against ${billboards.state.triangles}; ` +
            `cover ${coverage.toFixed(2)} of the billboards' ${boardPixels} pixels; ${against.psnr.toFixed(1)} dB from the billboards, no trees ${nothing.psnr.toFixed(1)} dB; ` +
            `over 4 x 4 blocks ${against.blockPsnr.toFixed(1)} and ${nothing.blockPsnr.toFixed(1)} dB`);
        assert.ok(coverage > 0.7 && coverage < 1.4, `the points cover ${coverage.toFixed(2)} of the billboards' pixels`);
        assert.ok(against.psnr > nothing.psnr + 2.5, `PSNR against the billboards: points ${against.psnr.toFixed(2)} dB, no trees ${nothing.psnr.toFixed(2)} dB`);
        assert.ok(against.blockPsnr > nothing.blockPsnr + 5, `over 4 x 4 blocks: points ${against.blockPsnr.toFixed(2)} dB, no trees ${nothing.blockPsnr.toFixed(2)} dB`);
    });
});
