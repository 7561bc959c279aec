// The viewer end to end (ctest web.browser): `hexlod serve` on a small scene of its own, Debian's
// chromium driven by playwright-core. It loads the viewer and waits for its cells, moves the
// camera with the keyboard, flies to a building and selects it with a click, raises its floors
// with the tuning panel's slider, and requires that the pixels of the building's screen region
// changed and that the stats show the batch's new version; a refused edit must show its reason.
// Screenshots go to $HEXLOD_WEB_ARTIFACTS.
import assert from 'node:assert/strict';
import path from 'node:path';
import test from 'node:test';

import { artifactsDir as artifacts, configsDir as configs, withServedScene } from './harness.mjs';


// About 30 buildings of both grammars, no trees, a coarse LOD budget: few terminals, so a frame
// stays well under a second on SwiftShader.
const scene = {
    name: 'browser-test', seed: 5, cell_size: 70,
    grammars: {
        business: { file: path.join(configs, 'grammars', 'business.grammar') },
        residential: { file: path.join(configs, 'grammars', 'residential.grammar') },
    },
    buildings: [{ source: 'procedural', count: 30, block_size: 60, street_width: 12,
        districts: [
            { grammar: 'business', share: 0.15, floors: [6, 9], lot: [24, 24] },
            { grammar: 'residential', share: 0.85, floors: [2, 4], lot: [16, 18] },
        ] }],
    lod: { max_screen_space_error: 12, hysteresis: 0.2, geometric_error: [16, 4, 1, 0.25, 0] },
};

// Share of pixels in `rect` whose colour moved by more than 24 (of 255) in any channel, decoded
// in the page (no PNG library needed here).
async function changedShare(page, before, after, rect) {
    return page.evaluate(
        async ({ a, b, rect }) => {
            const decode = async (base64) => {
                const bitmap = await createImageBitmap(await (await fetch(`data:image/png;base64,${base64}`)).blob());
                const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
                const context = canvas.getContext('2d');
                context.drawImage(bitmap, 0, 0);
                return context.getImageData(rect.x, rect.y, rect.width, rect.height).data;
            };
            const [pa, pb] = [await decode(a), await decode(b)];
            let changed = 0;
            for (let i = 0; i < pa.length; i += 4)
                if (Math.max(Math.abs(pa[i] - pb[i]), Math.abs(pa[i + 1] - pb[i + 1]), Math.abs(pa[i + 2] - pb[i + 2])) > 24) ++changed;
            return changed / (pa.length / 4);
        },
        { a: before.toString('base64'), b: after.toString('base64'), rect },
    );
}

test('the viewer loads, moves, selects a building, tunes it and shows the edit', { timeout: 240000 }, async () => {
    await withServedScene(scene, { impostorGrid: 4, viewport: { width: 800, height: 450 } }, async ({ base, page, pageErrors }) => {
        const shot = (name) => page.screenshot({ path: path.join(artifacts, name), timeout: 60000 });
        const stats = () => page.locator('#stats').textContent();

        // Load and wait for the cells.
        const started = Date.now();
        await page.goto(`${base}?aa=0`);
        await page.waitForFunction(() => window.hexlod?.idle(), null, { timeout: 90000 });
        const loadSeconds = (Date.now() - started) / 1000;
        const loaded = await page.evaluate(() => window.hexlod.state());
        assert.ok(loaded.cache.entries > 0, 'no payload loaded');
        assert.ok(loaded.streamer.visible > 0, 'no cell in view');
        // The service serves every shape's glTF mesh and the emitted shapes' impostors.
        const loadedStats = await stats();
        assert.match(loadedStats, /meshes (\d+)\/\1 glTF, (\d+)\/\2 glTF/);
        assert.match(loadedStats, /impostors [1-9]\d* atlases/);
        await shot('01-loaded.png');

        // Move the camera with the keyboard.
        await page.locator('#view').focus();
        const from = loaded.position.slice();
        await page.keyboard.down('w');
        await page.waitForFunction((z) => window.hexlod.controls.position.some((v, i) => Math.abs(v - z[i]) > 5), from, { timeout: 30000 });
        await page.keyboard.up('w');

        // Fly to the residential building nearest the city centre, look at it from its south side
        // and click where it shows: whichever building the click hits is the one selected.
        const target = await page.evaluate(() => {
            const h = window.hexlod;
            const residential = h.scene.grammars.find((g) => g.name === 'residential').index;
            let best = null;
            for (const cell of h.streamer.cells) {
                const batch = cell.batches.find((b) => b.grammar === residential && b.shown.extruded);
                if (!batch) continue;
                const set = h.streamer.cache.get(batch.shown.extruded).set;
                for (let i = 0; i < set.buildings.count; ++i) {
                    const b = set.buildings;
                    let x = 0, y = 0;
                    for (let k = 0; k < b.vertexCount[i]; ++k) {
                        x += set.footprints.x[b.firstVertex[i] + k] / b.vertexCount[i];
                        y += set.footprints.y[b.firstVertex[i] + k] / b.vertexCount[i];
                    }
                    const centre = [x + cell.origin[0], y + cell.origin[1], b.baseElevation[i] + cell.origin[2] + b.height[i] * 0.5];
                    const d = Math.hypot(centre[0], centre[1]);
                    if (!best || d < best.d) best = { d, id: b.id[i], cell: [cell.q, cell.r], grammar: residential, centre, height: b.height[i] };
                }
            }
            const c = best.centre;
            h.setCamera({ position: [c[0], c[1] - 50, c[2] + 20], yaw: Math.PI / 2, pitch: -Math.atan2(20, 50) });
            return best;
        });
        assert.ok(target, 'no residential building drawn');
        await page.waitForFunction(() => window.hexlod.idle(), null, { timeout: 90000 });
        await page.waitForTimeout(500);
        await shot('02-moved.png');
        const box = await page.locator('#view').boundingBox();
        await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
        await page.waitForFunction(() => /^Building \d+$/.test(document.querySelector('#tuning h2')?.textContent ?? ''), null, { timeout: 30000 });
        await page.waitForSelector('#tuning input[data-param="floors"]');
        const id = Number((await page.locator('#tuning h2').textContent()).split(' ')[1]);
        const facts = await page.locator('#tuning .facts').textContent();
        const info = await (await fetch(`${base}api/v1/buildings/${id}`)).json();
        assert.match(facts, new RegExp(`grammar ${info.grammar_name} \\(${info.grammar}\\)`));
        assert.match(facts, new RegExp(`cell ${info.cell[0]}, ${info.cell[1]}`));
        Object.assign(target, { id, cell: info.cell, grammar: info.grammar });
        const floors = Number(await page.locator('#tuning input[data-param="floors"]').inputValue());
        await page.waitForTimeout(500);
        const before = await shot('03-selected.png');
        const rect = await page.evaluate(() => window.hexlod.selectionRect());
        assert.ok(rect && rect.width > 10 && rect.height > 10, `selection rectangle ${JSON.stringify(rect)}`);

        // Raise it through the panel: the edit posts, its event comes back, the batch re-renders.
        const raised = floors <= 8 ? floors + 3 : floors - 3;
        const edited = Date.now();
        await page.locator('#tuning input[data-param="floors"]').fill(String(raised));
        const version = `(${target.cell[0]},${target.cell[1]})/${target.grammar} v2`;
        await page.waitForFunction((v) => document.getElementById('stats').textContent.includes(v), version, { timeout: 30000 });
        const editSeconds = (Date.now() - edited) / 1000;
        // The viewer's own timing of it: the POST's reply, then the first frame with the edited
        // batch at its new version.
        const timing = await page.evaluate(() => window.hexlod.state().lastEdit);
        assert.ok(timing && timing.inView, `the edited batch was drawn: ${JSON.stringify(timing)}`);
        assert.ok(timing.postedAt <= timing.repliedAt && timing.repliedAt <= timing.shownAt, JSON.stringify(timing));
        await page.waitForFunction(() => /last edit \d+: reply in [\d.]+ s, on screen [\d.]+ s after its POST/.test(document.getElementById('stats').textContent), null, { timeout: 10000 });
        await page.waitForFunction(() => window.hexlod.idle(), null, { timeout: 60000 });
        await page.waitForTimeout(700);
        const after = await shot('04-edited.png');
        assert.match(await stats(), new RegExp(version.replace(/[()]/g, '\\$&')));
        const building = await (await fetch(`${base}api/v1/buildings/${target.id}`)).json();
        assert.equal(building.params.floors, raised);
        assert.equal(building.batch.version, 2);

        // The region the building covered (grown upward by what it gained) changed.
        const scale = raised / floors;
        const grown = { ...rect, y: rect.y - rect.height * Math.max(scale - 1, 0), height: rect.height * Math.max(scale, 1) };
        const region = {
            x: Math.max(0, Math.floor(grown.x)), y: Math.max(0, Math.floor(grown.y)),
            width: Math.min(800 - Math.max(0, Math.floor(grown.x)), Math.ceil(grown.width)),
            height: Math.min(450 - Math.max(0, Math.floor(grown.y)), Math.ceil(grown.height)),
        };
        const share = await changedShare(page, before, after, region);
        assert.ok(share > 0.05, `only ${(100 * share).toFixed(1)} % of the building's region changed`);

        // A refused edit shows the service's reason in the panel.
        await page.evaluate((id) => window.hexlod.tuning.post({ buildings: [id] }, { floors: 99 }), target.id);
        await page.waitForFunction(() => /outside/.test(document.getElementById('edit-error')?.textContent ?? ''), null, { timeout: 10000 });

        const final = await page.evaluate(() => window.hexlod.state());
        assert.deepEqual(pageErrors, []);
        console.log(
            `web.browser: first view ${loadSeconds.toFixed(2)} s (viewer: ${final.loadTime?.toFixed(2)} s), ` +
                `edit to new version on screen ${editSeconds.toFixed(2)} s (viewer: reply ${((timing.repliedAt - timing.postedAt) / 1000).toFixed(2)} s, ` +
                `drawn ${((timing.shownAt - timing.postedAt) / 1000).toFixed(2)} s after the POST), ${(100 * share).toFixed(1)} % of the region changed, ` +
                `${final.fps.toFixed(1)} fps, ${(final.traffic.bytes / 1024).toFixed(0)} KiB in ${final.traffic.requests} requests; ` +
                `artifacts in ${artifacts}`,
        );
    });
});
