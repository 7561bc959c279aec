// Where the viewer's frame goes, for docs/BENCHMARKS.md: `hexlod serve --scene S`, chromium
// (the browser test's setup), the opening view until every wanted payload is drawn, then
// frames rendered by hand, each timed until a one-pixel readPixels returns (so the time
// includes the GL work, which gl.finish() in chromium does not wait for):
// - the whole frame, with its draw calls, triangles and terminals per LOD, and the cache's
//   bytes (payloads and the GPU buffers made from them), in all and by payload kind, with the
//   cells in view per LOD and those whose terminal sets the budget held back;
// - the frame without the impostor meshes (LOD2 and LOD3, and the tree billboards), and
//   without the tree billboards alone;
// - the whole frame with a one-pixel scissor, which leaves the vertex and primitive work and
//   drops nearly all of the fill.
// Prints one JSON object, times in milliseconds (median of 5 frames each).
//   node web/bench/frame_cost.mjs HEXLOD_BINARY SCENE [WIDTHxHEIGHT] [VIEWER_QUERY]
import { launchChromium, startServer } from '../test-browser/harness.mjs';

const [binary, scene, size = '960x540', query = ''] = process.argv.slice(2);
if (!binary || !scene) {
    console.error('usage: node web/bench/frame_cost.mjs HEXLOD_BINARY SCENE [WIDTHxHEIGHT] [VIEWER_QUERY]');
    process.exit(2);
}
const [width, height] = size.split('x').map(Number);
const server = startServer(binary, scene);
const browser = await launchChromium({ width, height });
const page = browser.page;
try {
    const base = await server.url;
    await page.goto(`${base}?aa=0${query ? `&${query}` : ''}`);
    await page.waitForFunction(() => window.hexlod?.idle(), null, { timeout: 600000, polling: 500 });
    const result = await page.evaluate(() => {
        const { world } = window.hexlod;
        const gl = world.renderer.getContext();
        const pixel = new Uint8Array(4);
        const frame = () => {
            const start = performance.now();
            world.renderer.render(world.scene, world.camera);
            gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
            return performance.now() - start;
        };
        const median = () => {
            const times = Array.from({ length: 5 }, frame).sort((a, b) => a - b);
            return times[2];
        };
        const impostors = [];
        world.scene.traverse((o) => {
            // Terminal impostors and tree billboards both sample atlases.
            if (o.isMesh && o.visible && o.material?.uniforms?.atlasLayout) impostors.push(o);
        });
        const out = {
            impostor_meshes: impostors.length,
            impostor_instances: impostors.reduce((sum, o) => sum + o.count, 0),
            frame_ms: median(),
        };
        out.draw_calls = world.renderer.info.render.calls;
        out.triangles = world.renderer.info.render.triangles;
        const state = window.hexlod.state();
        out.terminals = state.streamer.terminals; // per LOD, and LOD4 drawn with coarse meshes
        out.cache = state.cache; // payloads and what they hold for the GPU, in bytes
        out.cells = state.streamer.cells; // in view, per LOD, and those the budget held back
        out.point_batches = state.streamer.pointBatches; // extruded batches whose buildings are points
        out.tree_points = state.streamer.trees.points; // far trees drawn as points
        out.terminal_budget = state.terminalBudget;
        // The cache's bytes by payload kind and grammar kind ("terminal building", "extruded tree", ...).
        // And per building grammar, the bytes its terminal sets take per building.
        out.cache_by_kind = {};
        const perGrammar = {};
        for (const { value, bytes } of window.hexlod.streamer.cache.list()) {
            const grammar = window.hexlod.streamer.grammar(value.grammar);
            const kind = `${value.kind} ${grammar?.kind}`;
            out.cache_by_kind[kind] = (out.cache_by_kind[kind] ?? 0) + bytes;
            if (kind !== 'terminal building') continue;
            const sum = (perGrammar[grammar.label] ??= { bytes: 0, members: 0 });
            sum.bytes += bytes;
            sum.members += value.members;
        }
        out.terminal_bytes_per_building = Object.fromEntries(Object.entries(perGrammar).map(([k, v]) => [k, Math.round(v.bytes / v.members)]));
        impostors.forEach((o) => (o.visible = false));
        out.without_impostors_ms = median();
        impostors.forEach((o) => (o.visible = true));
        const billboards = impostors.filter((o) => !o.material.uniforms.nominal); // terminals' have a nominal size
        out.tree_billboards = billboards.reduce((sum, o) => sum + o.count, 0);
        billboards.forEach((o) => (o.visible = false));
        out.without_tree_billboards_ms = median();
        billboards.forEach((o) => (o.visible = true));
        world.renderer.setScissorTest(true);
        world.renderer.setScissor(0, 0, 1, 1);
        out.one_pixel_scissor_ms = median();
        world.renderer.setScissorTest(false);
        return out;
    });
    console.log(JSON.stringify({ scene, viewport: size, query, ...result }, null, 1));
} finally {
    await browser.close();
    server.stop();
}
