// How long the viewer takes to load a view, for docs/BENCHMARKS.md: `hexlod serve --scene S`,
// chromium (the browser test's setup), one viewer URL; every 10 s it prints the seconds since
// the page was opened and what the viewer holds (cache entries and bytes, requests pending, the
// frame rate, the last frame's triangles, the extruded batches drawn as points, the tree
// billboards and points), until the viewer is idle (everything it wants drawn) or
// LIMIT_SECONDS pass; then one line with the median of 5 frames rendered by hand, each timed
// until a one-pixel readPixels returns, with their draw calls, triangles and points. A view
// that frame_cost.mjs cannot time, because it does not settle within that script's ten
// minutes, is measured here.
//   node web/bench/settle_time.mjs HEXLOD_BINARY SCENE WIDTHxHEIGHT VIEWER_QUERY [LIMIT_SECONDS]
import { launchChromium, startServer } from '../test-browser/harness.mjs';

const [binary, scene, size, query, limit = '900'] = process.argv.slice(2);
if (!binary || !scene || !size || query === undefined) {
    console.error('usage: node web/bench/settle_time.mjs HEXLOD_BINARY SCENE WIDTHxHEIGHT VIEWER_QUERY [LIMIT_SECONDS]');
    process.exit(2);
}
const [width, height] = size.split('x').map(Number);
const server = startServer(binary, scene);
const browser = await launchChromium({ width, height });
const page = browser.page;
const started = Date.now();
const seconds = () => Math.round((Date.now() - started) / 1000);
try {
    await page.goto(`${await server.url}?aa=0${query ? `&${query}` : ''}`);
    let idle = false;
    while (!idle && seconds() < Number(limit)) {
        await page.waitForTimeout(10000);
        const sample = await page.evaluate(() => {
            const s = window.hexlod?.state();
            if (!s) return null;
            return {
                entries: s.cache.entries, bytes: s.cache.bytes, pending: s.pending, fps: Number(s.fps.toFixed(2)), triangles: s.triangles,
                point_batches: s.streamer.pointBatches, tree_billboards: s.streamer.trees.billboards, tree_points: s.streamer.trees.points, idle: window.hexlod.idle(),
            };
        });
        idle = sample?.idle ?? false;
        console.log(JSON.stringify({ seconds: seconds(), ...sample }));
    }
    const frame = await page.evaluate(() => {
        const { world } = window.hexlod;
        const gl = world.renderer.getContext();
        const pixel = new Uint8Array(4);
        const times = Array.from({ length: 5 }, () => {
            const start = performance.now();
            world.renderer.render(world.scene, world.camera);
            gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
            return performance.now() - start;
        }).sort((a, b) => a - b);
        const { calls, triangles, points } = world.renderer.info.render;
        return { frame_ms: times[2], draw_calls: calls, triangles, points };
    });
    console.log(JSON.stringify({ seconds: seconds(), settled: idle, scene, viewport: size, query, ...frame }));
} finally {
    await browser.close();
    server.stop();
}
