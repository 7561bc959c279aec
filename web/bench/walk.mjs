// The viewer on a real scene, for docs/BENCHMARKS.md: `hexlod serve --scene S`, chromium (the
// browser test's setup), then the opening view until every wanted payload is drawn (load
// time), the frame rate over a few seconds of it, and a street-level walk of W seconds at
// walking speed through the middle of the city (bytes and requests it costs, frame rate). The
// walk is paced by the clock, not by frames, so a slow software renderer walks as far.
//   node web/bench/walk.mjs HEXLOD_BINARY SCENE [WALK_SECONDS] [WIDTHxHEIGHT] [VIEWER_QUERY]
// VIEWER_QUERY is added to the viewer's URL, e.g. 'camera=0,-400,1.7,90,0' for a street-level opening view.
import { launchChromium, startServer } from '../test-browser/harness.mjs';

const [binary, scene, walkArg = '20', size = '960x540', query = ''] = process.argv.slice(2);
if (!binary || !scene) {
    console.error('usage: node web/bench/walk.mjs HEXLOD_BINARY SCENE [WALK_SECONDS] [WIDTHxHEIGHT] [VIEWER_QUERY]');
    process.exit(2);
}
const [width, height] = size.split('x').map(Number);
const server = startServer(binary, scene);
const browser = await launchChromium({ width, height });
const page = browser.page;
const state = () => page.evaluate(() => window.hexlod.state());
const fpsOver = async (ms) => {
    const frames = await page.evaluate(
        (ms) => new Promise((resolve) => {
            let n = 0;
            const t0 = performance.now();
            const tick = (t) => (t - t0 < ms ? (++n, requestAnimationFrame(tick)) : resolve({ n, ms: t - t0 }));
            requestAnimationFrame(tick);
        }),
        ms,
    );
    return (1000 * frames.n) / frames.ms;
};
try {
    const base = await server.url;
    const t0 = Date.now();
    await page.goto(`${base}?aa=0${query ? `&${query}` : ''}`);
    await page.waitForFunction(() => window.hexlod?.idle(), null, { timeout: 600000, polling: 500 });
    const opening = await state();
    const load = { seconds: (Date.now() - t0) / 1000, viewer_seconds: opening.loadTime, bytes: opening.traffic.bytes, requests: opening.traffic.requests };
    const openingFps = await fpsOver(5000);
    const terminals = opening.streamer.terminals;
    // Walk: eye height, 1.4 m/s north through the centre of the cell index.
    await page.evaluate(() => {
        const h = window.hexlod;
        const cells = h.streamer.cells;
        const x = cells.reduce((s, c) => s + c.origin[0], 0) / cells.length;
        const y = Math.min(...cells.map((c) => c.origin[1]));
        h.setCamera({ position: [x, y, 0], yaw: Math.PI / 2, pitch: 0 });
        h.controls.setMode('walk');
        h.walkStart = { x, y, t: performance.now() };
        h.walkTimer = setInterval(() => {
            const s = h.walkStart;
            h.setCamera({ position: [s.x, s.y + 1.4 * ((performance.now() - s.t) / 1000), 0] });
        }, 100);
    });
    const before = await state();
    const walkSeconds = Number(walkArg);
    const walkFps = await fpsOver(walkSeconds * 1000);
    await page.evaluate(() => clearInterval(window.hexlod.walkTimer));
    const after = await state();
    console.log(JSON.stringify({
        scene, viewport: size, query,
        opening: { ...load, fps: openingFps, cells: opening.streamer.cells, terminals, trees: opening.streamer.trees, cache_mib: opening.cache.bytes / 1048576 },
        walk: {
            seconds: walkSeconds, metres: Math.hypot(after.position[0] - before.position[0], after.position[1] - before.position[1]),
            fps: walkFps, bytes: after.traffic.bytes - before.traffic.bytes, requests: after.traffic.requests - before.traffic.requests,
            cache_mib: after.cache.bytes / 1048576, evictions: after.cache.evictions,
        },
    }, null, 1));
} finally {
    await browser.close();
    server.stop();
}
