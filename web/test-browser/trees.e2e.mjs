// Tree billboards end to end (part of ctest web.browser): `hexlod serve` on a park of its own
// (40 trees of the shipped species, a few houses) in chromium. From 150 m the same view is drawn
// with every tree as terminals, as billboards of its species' impostor, and without trees; the
// billboards must cover about the pixels the terminals cover and bring the image much closer to
// the terminals' than no trees at all, and draw the same over their species' boxes as over their
// spheres' whole squares; drawn as terminals this far out, the trees' parts use
// their coarse meshes, with fewer triangles and an image close to the full meshes' (?coarse=0);
// by distance (the default) the cut must split the park's batches from nearer (and with no
// budget for terminal sets draw the near trees as billboards too) and make every tree a
// billboard from farther; and after the trees are edited, the service bakes species for
// their new values and the far trees are billboards of those, changing the image; and at eye
// level in a small viewport the ground is drawn. Screenshots go to $HEXLOD_WEB_ARTIFACTS.
import assert from 'node:assert/strict';
import path from 'node:path';
import test from 'node:test';

import { artifactsDir as artifacts, parkScene, withServedScene } from './harness.mjs';

const width = 800, height = 450;

const scene = parkScene({ name: 'tree-test', seed: 3, cellSize: 60, houses: 4, parkShare: 0.5, trees: 40 });

// Per image pair, decoded in the page: the pixels each of two images changes against a third
// (more than 24 of 255 in a channel), the overlap of those masks, and PSNR between images.
async function compare(page, shots) {
    return page.evaluate(async (shots) => {
        const decode = async (base64) => {
            const bitmap = await createImageBitmap(await (await fetch(`data:image/png;base64,${base64}`)).blob());
            const context = new OffscreenCanvas(bitmap.width, bitmap.height).getContext('2d');
            context.drawImage(bitmap, 0, 0);
            return context.getImageData(0, 0, bitmap.width, bitmap.height).data;
        };
        const [none, terminals, billboards] = await Promise.all([shots.none, shots.terminals, shots.billboards].map(decode));
        const moved = (a, b, i) => Math.max(Math.abs(a[i] - b[i]), Math.abs(a[i + 1] - b[i + 1]), Math.abs(a[i + 2] - b[i + 2])) > 24;
        const psnr = (a, b) => {
            let se = 0;
            for (let i = 0; i < a.length; i += 4) for (let k = 0; k < 3; ++k) se += (a[i + k] - b[i + k]) ** 2;
            return 10 * Math.log10((255 * 255) / (se / ((3 * a.length) / 4)));
        };
        let t = 0, b = 0, both = 0, either = 0;
        for (let i = 0; i < none.length; i += 4) {
            const mt = moved(terminals, none, i), mb = moved(billboards, none, i);
            t += mt;
            b += mb;
            both += mt && mb;
            either += mt || mb;
        }
        return { terminalPixels: t, billboardPixels: b, overlap: both / either, psnrBillboards: psnr(terminals, billboards), psnrNone: psnr(terminals, none) };
    }, shots);
}

test('far trees are billboards that stand for their trees, and edited trees get species of their own', { timeout: 240000 }, async () => {
    await withServedScene(scene, { impostorGrid: 6, viewport: { width, height } }, async ({ base, page, pageErrors }) => {
        // South of the park at eye height, 150 m from its nearest cell and farther; by distance,
        // trees are billboards from 195 m at this viewport.
        const near = '0,-300,4,90,0', far = '0,-400,4,90,0';
        const view = async (trees, camera = near, options = '') => {
            await page.goto(`${base}?camera=${camera}&trees=${trees}${options}`);
            await page.waitForFunction(() => window.hexlod?.idle(), null, { timeout: 90000 });
            await page.evaluate(() => document.querySelectorAll('#stats, #tuning, #help, #messages').forEach((e) => (e.style.visibility = 'hidden')));
            await page.waitForTimeout(500);
            const image = await page.screenshot({ path: path.join(artifacts, `trees-${trees}${options.replace(/[&=]/g, '-')}.png`), timeout: 60000 });
            return { image: image.toString('base64'), state: await page.evaluate(() => window.hexlod.state()) };
        };
        // Per drawn billboard mesh, the width of the box its quads cover as a share of its
        // species sphere's diameter (1: the whole square).
        const boxWidths = () => page.evaluate(() => {
            const widths = [];
            window.hexlod.world.scene.traverse((o) => {
                const u = o.material?.uniforms;
                if (o.isMesh && o.count > 0 && u?.boxLo) widths.push((u.boxHi.value.x - u.boxLo.value.x) / (2 * u.sphere.value.w));
            });
            return widths;
        });
        const none = await view('none');
        const terminals = await view('terminals');
        const billboards = await view('billboards');
        const boxes = await boxWidths();
        const scene = await (await fetch(`${base}api/v1/scene`)).json();
        assert.equal(scene.capabilities.tree_billboards, true);
        assert.equal(billboards.state.streamer.trees.billboards, 40, 'every tree is a billboard');
        assert.equal(terminals.state.streamer.trees.billboards, 0);
        assert.match(billboards.state.trees, /^\d+ species$/);
        // This far out every tree part with a coarse mesh draws it; with ?coarse=0 none does, and
        // the two images differ by the meshes' deviation, under the error budget.
        const full = await view('terminals', near, '&coarse=0');
        const treeParts = terminals.state.streamer.terminals;
        assert.ok(treeParts.coarse > 0 && treeParts.coarse <= treeParts[4], `terminals ${JSON.stringify(treeParts)}`);
        assert.equal(full.state.streamer.terminals.coarse, 0);
        assert.equal(full.state.streamer.terminals[4], treeParts[4]);
        const triangleShare = terminals.state.triangles / full.state.triangles;
        assert.ok(triangleShare < 0.9, `coarse meshes draw ${terminals.state.triangles} of ${full.state.triangles} triangles`);
        const coarseError = await compare(page, { none: none.image, terminals: full.image, billboards: terminals.image });
        assert.ok(coarseError.psnrBillboards > 30, `coarse against full meshes: ${coarseError.psnrBillboards.toFixed(2)} dB`);

        const c = await compare(page, { none: none.image, terminals: terminals.image, billboards: billboards.image });
        const coverage = c.billboardPixels / c.terminalPixels;
        assert.ok(c.terminalPixels > 300, `the trees cover ${c.terminalPixels} pixels`);
        assert.ok(coverage > 0.7 && coverage < 1.4, `billboards cover ${coverage.toFixed(2)} of the terminals' pixels`);
        // Each tree grows from its own seed; the species' impostor shows one tree of them.
        assert.ok(c.overlap > 0.45, `the two tree masks overlap by ${c.overlap.toFixed(2)}`);
        assert.ok(c.psnrBillboards > c.psnrNone + 3, `PSNR against the terminals: billboards ${c.psnrBillboards.toFixed(2)} dB, no trees ${c.psnrNone.toFixed(2)} dB`);
        // Over their species' boxes or over their spheres' whole squares (?treeboxes=0), the
        // billboards draw the same trees: the squares' other pixels show nothing.
        const squares = await view('billboards', near, '&treeboxes=0');
        const squareWidths = await boxWidths();
        assert.ok(boxes.length > 0 && boxes.every((w) => w < 0.95), `billboards over boxes ${boxes.map((w) => w.toFixed(2))} of their squares' width`);
        assert.ok(squareWidths.length === boxes.length && squareWidths.every((w) => Math.abs(w - 1) < 1e-6), `squares ${squareWidths}`);
        const fit = await compare(page, { none: none.image, terminals: squares.image, billboards: billboards.image });
        assert.ok(fit.psnrBillboards > 45, `billboards over boxes against squares: ${fit.psnrBillboards.toFixed(2)} dB`);
        assert.ok(Math.abs(fit.billboardPixels - fit.terminalPixels) <= 0.01 * fit.terminalPixels,
            `the trees cover ${fit.billboardPixels} pixels over boxes and ${fit.terminalPixels} over squares`);

        // Nearer, the cut runs through the park: its near trees are terminals, its far ones
        // billboards, in the same batches.
        const mixed = (await view('auto', '0,-200,4,90,0')).state.streamer.trees;
        assert.ok(mixed.billboards > 0 && mixed.terminals > 0, `trees ${JSON.stringify(mixed)}`);
        assert.equal(mixed.billboards + mixed.terminals, 40);
        // With no room for terminal sets (?budget=0) the near trees' sets are held back, and
        // those trees are billboards too, not missing.
        const held = (await view('auto', '0,-200,4,90,0', '&budget=0')).state;
        assert.deepEqual([held.streamer.trees.billboards, held.streamer.trees.terminals], [40, 0], `trees ${JSON.stringify(held.streamer.trees)}`);
        assert.ok(held.streamer.cells.held > 0, `cells ${JSON.stringify(held.streamer.cells)}`);

        // By distance, trees beyond the terminal distance are billboards.
        const auto = await view('auto', far);
        assert.equal(auto.state.streamer.trees.billboards, 40);
        assert.equal(auto.state.streamer.terminals[4], 0, 'no tree terminal this far out (the houses are LOD3 and LOD2)');

        // Edit the trees' grammar (trees are edited by cell or grammar): no species baked at start
        // has the new values. Until the service has baked theirs, the edited trees are terminals
        // at any distance; once its species events are in, every tree is a billboard again, of
        // its new species, at the batches' new version.
        const editStart = Date.now();
        const edited = await page.evaluate(async () => {
            const h = window.hexlod;
            const grammar = h.scene.grammars.find((g) => g.kind === 'tree');
            await h.tuning.post({ grammar: grammar.index }, { trunk_h: 4.25 });
            return { grammar: grammar.index, trunk: grammar.parameters.findIndex((p) => p.name === 'trunk_h') };
        });
        await page.waitForFunction(
            (e) => {
                const h = window.hexlod;
                const trees = h.state().streamer.trees;
                const drawn = h.streamer.cells.flatMap((c) => c.batches.filter((b) => b.grammar === e.grammar).map((b) => b.drawn));
                return h.idle() && trees.billboards === 40 && trees.edited === 0 && drawn.every((d) => d?.kind === 'billboards' && d.version === 2);
            },
            edited,
            { timeout: 90000 },
        );
        const rebillboarded = (Date.now() - editStart) / 1000;
        const after = await page.evaluate(() => window.hexlod.state());
        const rebaked = await (await fetch(`${base}api/v1/scene`)).json();
        const added = rebaked.tree_species.slice(scene.tree_species.length);
        assert.ok(added.length > 0, 'the service baked species for the edited trees');
        for (const s of added) assert.equal(s.parameters[edited.trunk], 4.25, `species ${s.name}`);
        assert.equal(after.trees, `${rebaked.tree_species.length} species`);
        await page.waitForTimeout(500);
        const editedImage = (await page.screenshot({ timeout: 60000 })).toString('base64');
        // The pixels the edit changed against the view before it (compare's first count).
        const changed = (await compare(page, { none: auto.image, terminals: editedImage, billboards: editedImage })).terminalPixels;
        assert.ok(changed > 50, `the edited trees' billboards change ${changed} pixels`);
        await page.screenshot({ path: path.join(artifacts, 'trees-edited.png'), timeout: 60000 });

        // The ground at eye level, level, in a small viewport: SwiftShader clipped a ground of
        // large triangles so that there it hid the bottoms of the houses and trees, or came out
        // fully fogged (the sky's colour). Rendered with and without it, no pixel of anything
        // else may change beyond a few at the houses' bases, and below the horizon no pixel
        // may stay the sky's colour.
        await page.setViewportSize({ width: 640, height: 360 });
        await view('none', '0,-200,1.7,90,0', '&mode=walk&aa=0');
        const ground = await page.evaluate(() => {
            const w = window.hexlod.world, gl = w.renderer.getContext();
            const W = gl.drawingBufferWidth, H = gl.drawingBufferHeight;
            const grab = () => {
                w.renderer.render(w.scene, w.camera);
                const pixels = new Uint8Array(4 * W * H);
                gl.readPixels(0, 0, W, H, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
                return pixels;
            };
            const s = w.scene.background.clone().convertLinearToSRGB();
            const sky = [s.r, s.g, s.b].map((c) => Math.round(255 * c));
            const far = (a, i, b) => Math.abs(a[i] - b[0]) + Math.abs(a[i + 1] - b[1]) + Math.abs(a[i + 2] - b[2]);
            w.ground.visible = false;
            const bare = grab();
            w.ground.visible = true;
            const full = grab();
            let objects = 0, hidden = 0, skyBelow = 0;
            for (let i = 0; i < W * H; ++i) {
                const o = 4 * i;
                if (far(bare, o, sky) > 6) {
                    ++objects;
                    if (far(full, o, [bare[o], bare[o + 1], bare[o + 2]]) > 30) ++hidden;
                } else if (i < W * (H / 2 - 2) && far(full, o, sky) <= 6) ++skyBelow; // rows from the bottom
            }
            return { objects, hidden, skyBelow };
        });
        assert.ok(ground.objects > 1000, `the view shows ${ground.objects} pixels of houses and trees`);
        assert.ok(ground.hidden <= ground.objects / 1000, `the ground hides ${ground.hidden} of ${ground.objects} pixels of houses and trees`);
        assert.equal(ground.skyBelow, 0, 'pixels below the horizon left the sky\'s colour');
        assert.deepEqual(pageErrors, []);
        console.log(
            `web.browser trees: billboards cover ${coverage.toFixed(2)} of the terminals' ${c.terminalPixels} pixels (overlap ${c.overlap.toFixed(2)}), ` +
                `PSNR against terminals ${c.psnrBillboards.toFixed(2)} dB (no trees: ${c.psnrNone.toFixed(2)} dB); ` +
                `over boxes (${boxes.map((w) => w.toFixed(2)).join(', ')} of the squares' width) against squares ${fit.psnrBillboards.toFixed(2)} dB, ${fit.billboardPixels} and ${fit.terminalPixels} tree pixels; ` +
                `coarse meshes for ${treeParts.coarse} of ${treeParts[4]} LOD4 terminals: ${terminals.state.triangles} triangles against ${full.state.triangles}, ` +
                `${coarseError.psnrBillboards.toFixed(2)} dB against full meshes; ` +
                `first view ${terminals.state.loadTime?.toFixed(2)} s with terminals, ${billboards.state.loadTime?.toFixed(2)} s with billboards; ` +
                `after the edit, ${added.length} species baked and every tree a billboard again in ${rebillboarded.toFixed(2)} s, ${changed} pixels changed; ` +
                `at eye level the ground hides ${ground.hidden} of ${ground.objects} pixels of houses and trees`,
        );
    });
});
