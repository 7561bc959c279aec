// The viewer's cache budget end to end (part of ctest web.browser): `hexlod serve` on blocks of
// houses of its own, the opening view over them. With a budget that holds every terminal set
// the view wants, none is held back; with one that holds all but the farthest, the cache stays
// within it, the nearest terminal cells keep their terminals, the farther ones draw their
// extruded sets (LOD0), and no batch in view draws nothing. ?budget=0 holds every set back;
// malformed options are refused with a message and their defaults used. Screenshots go to
// $HEXLOD_WEB_ARTIFACTS.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import test from 'node:test';

import { artifactsDir as artifacts, housesScene, settledView, withServedScene } from './harness.mjs';

const MiB = 1024 * 1024;

const scene = housesScene({ name: 'budget-test', seed: 5, cellSize: 60, count: 40, floors: [2, 4] });

// Per visible cell: its LOD, its distance, and per batch what it draws.
async function cellsInView(page) {
    return page.evaluate(() => {
        const h = window.hexlod;
        return h.streamer.cells
            .filter((c) => h.world.cellGroup(c).visible)
            .map((c) => ({ id: c.id, lod: c.lod, distance: c.distance, drawn: c.batches.map((b) => b.drawn?.kind ?? null) }));
    });
}

// The cache's bytes of the building terminal sets of the cells in view, by distance, and of
// everything else.
async function cacheSplit(page) {
    return page.evaluate(() => {
        const h = window.hexlod;
        const inView = new Map(); // terminal set url -> its cell's distance
        for (const c of h.streamer.cells)
            if (h.world.cellGroup(c).visible) for (const b of c.batches) inView.set(b.terminal_set, c.distance);
        const terminals = [];
        let rest = 0;
        for (const { url, value, bytes } of h.streamer.cache.list()) {
            if (value.kind === 'terminal' && h.streamer.grammar(value.grammar)?.kind !== 'tree' && inView.has(url))
                terminals.push({ bytes, distance: inView.get(url) });
            else rest += bytes;
        }
        return { terminals: terminals.sort((a, b) => a.distance - b.distance).map((t) => t.bytes), rest };
    });
}

test('the cache budget holds the farthest terminal cell at LOD0 and the cache within it', { timeout: 300000 }, async () => {
    await withServedScene(scene, { impostorGrid: 4, viewport: { width: 640, height: 360 } }, async ({ base, page, pageErrors }) => {
        const whole = await settledView(page, `${base}?aa=0`);
        const split = await cacheSplit(page);
        const wholeCells = await cellsInView(page);
        const terminalCells = wholeCells.filter((c) => c.lod === 'terminals');
        assert.ok(terminalCells.length >= 3, `terminal cells in view: ${JSON.stringify(wholeCells)}`);
        assert.equal(whole.state.streamer.cells.held, 0);
        assert.equal(whole.state.terminalBudget.admitted, whole.state.terminalBudget.wanted);

        // Room for every terminal set in view but half of the farthest one.
        const sum = (bytes) => bytes.reduce((a, b) => a + b, 0);
        const budget = (split.rest + sum(split.terminals) - 0.5 * split.terminals.at(-1)) / MiB;
        const tight = await settledView(page, `${base}?aa=0&budget=${budget.toFixed(3)}`);
        const tightCells = await cellsInView(page);
        const stats = await page.locator('#stats').textContent();
        fs.writeFileSync(path.join(artifacts, 'budget-whole.png'), whole.image);
        fs.writeFileSync(path.join(artifacts, 'budget-tight.png'), tight.image);
        console.log(`budget: ${(sum(split.terminals) / MiB).toFixed(1)} MiB of terminal sets in view, ${(split.rest / MiB).toFixed(1)} MiB else; at ${budget.toFixed(1)} MiB, ${tight.state.streamer.cells.held} cells held, ${(tight.state.cache.bytes / MiB).toFixed(1)} MiB cached`);
        assert.deepEqual(pageErrors, []);
        assert.ok(tight.state.cache.bytes <= budget * MiB, `${tight.state.cache.bytes} bytes cached`);
        assert.ok(tight.state.streamer.cells.held > 0, JSON.stringify(tight.state.streamer.cells));
        assert.ok(tight.state.terminalBudget.admitted > 0, JSON.stringify(tight.state.terminalBudget));
        assert.match(stats, /held back by the cache budget/);
        for (const c of tightCells) assert.ok(c.drawn.every((kind) => kind !== null), `cell ${c.id} draws ${c.drawn}`);
        // A held cell lies no nearer than any cell that kept its terminals (the room leaves out
        // only the farthest set, and every nearer one comes before it).
        const terminalsIn = (c) => c.lod === 'terminals' && c.drawn.includes('terminal');
        const heldIn = (c) => c.lod === 'terminals' && !c.drawn.includes('terminal');
        const kept = tightCells.filter(terminalsIn), held = tightCells.filter(heldIn);
        assert.ok(kept.length > 0 && held.length > 0, JSON.stringify(tightCells));
        assert.ok(Math.max(...kept.map((c) => c.distance)) <= Math.min(...held.map((c) => c.distance)), JSON.stringify(tightCells));

        // budget=0: every terminal set held back, only what every frame pins is cached.
        const none = await settledView(page, `${base}?aa=0&budget=0`);
        assert.equal(none.state.terminalBudget.admitted, 0);
        assert.equal(none.state.streamer.terminals[4] + none.state.streamer.terminals[3] + none.state.streamer.terminals[2], 0);
        for (const c of await cellsInView(page)) assert.ok(c.drawn.every((kind) => kind === 'extruded'), `cell ${c.id} draws ${c.drawn}`);

        // Malformed options: refused, said so, and the defaults used (the budget's holds
        // everything; the opening view's camera, the trees by distance).
        const bad = await settledView(page, `${base}?aa=0&budget=lots&concurrency=0&trees=billbords&camera=1,2`);
        const messages = await page.locator('#messages').textContent();
        assert.match(messages, /\?budget=lots refused: budget must be a number from 0 to 65536; using 1024/);
        assert.match(messages, /\?concurrency=0 refused/);
        assert.match(messages, /\?trees=billbords refused/);
        assert.match(messages, /\?camera=1,2 refused/);
        assert.deepEqual(bad.state.position, whole.state.position, 'the opening view');
        assert.equal(bad.state.cache.budget, 1024 * MiB);
        assert.equal(bad.state.streamer.cells.held, 0);
    });
});
