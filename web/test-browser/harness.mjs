// What the browser tests and the benchmarks share: `hexlod serve` as a child process (its
// printed URL parsed), Debian's chromium under playwright-core with a fresh profile, the
// viewer's settled view of a URL, and how far apart two images are.
//
// WebGL without a GPU: chromium falls back to SwiftShader (ANGLE on its Vulkan device) under
// --disable-gpu; --use-angle=swiftshader --enable-unsafe-swiftshader ask for it explicitly, since
// newer builds refuse the silent fallback. Never `npx playwright install`: the browser is the
// Debian package (scripts/install-deps.sh).
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { chromium } from 'playwright-core';

export const webRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', 'dist');

export const CHROMIUM_ARGS = [
    '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync',
    '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
];

// {url: Promise of the viewer's URL, stop(), log()}.
export function startServer(binary, scene, extraArgs = []) {
    if (!fs.existsSync(path.join(webRoot, 'viewer.js'))) throw new Error('web/dist is not built: build the CMake target web');
    const child = spawn(binary, ['serve', '--scene', scene, '--port', '0', '--web-root', webRoot, ...extraArgs], {
        stdio: ['ignore', 'pipe', 'pipe'],
    });
    let log = '';
    const url = new Promise((resolve, reject) => {
        const timer = setTimeout(() => reject(new Error(`hexlod serve printed no URL in 60 s:\n${log}`)), 60000);
        const take = (chunk) => {
            log += chunk;
            const m = log.match(/viewer at (http:\/\/[^\s]+\/)/);
            if (m) {
                clearTimeout(timer);
                resolve(m[1]);
            }
        };
        child.stdout.on('data', take);
        child.stderr.on('data', take);
        child.on('exit', (code) => reject(new Error(`hexlod serve exited with ${code}:\n${log}`)));
    });
    return { url, log: () => log, stop: () => child.kill('SIGTERM') };
}

// A persistent context with a fresh profile folder (removed on close) and its first page.
export async function launchChromium(viewport) {
    const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'hexlod-chromium-'));
    const context = await chromium.launchPersistentContext(profile, {
        executablePath: '/usr/bin/chromium',
        headless: true,
        args: CHROMIUM_ARGS,
        viewport,
    });
    const page = context.pages()[0] ?? (await context.newPage());
    return {
        page,
        close: async () => {
            await context.close();
            fs.rmSync(profile, { recursive: true, force: true });
        },
    };
}

// The viewer at `url` once everything it wants is loaded and a few frames later, so that its
// lists are sorted for what it drew last: {state: window.hexlod.state(), image: the canvas
// alone, without the panels over it, as a PNG Buffer}.
export async function settledView(page, url, timeout = 90000) {
    await page.goto(url);
    await page.waitForFunction(() => window.hexlod?.idle(), null, { timeout, polling: 250 });
    for (let i = 0; i < 4; ++i) await page.evaluate(() => new Promise((done) => requestAnimationFrame(() => done())));
    await page.waitForFunction(() => window.hexlod.idle(), null, { timeout, polling: 250 });
    const state = await page.evaluate(() => window.hexlod.state());
    const png = await page.evaluate(() => document.getElementById('view').toDataURL('image/png'));
    return { state, image: Buffer.from(png.split(',')[1], 'base64') };
}

// The stats panel's text once it shows `text`: the panel is refreshed every 250 ms, so a state
// read just now may be newer than it. The text it has after `timeout` ms otherwise.
export async function statsShowing(page, text, timeout = 5000) {
    await page.waitForFunction((t) => document.getElementById('stats').textContent.includes(t), text, { timeout, polling: 50 }).catch(() => {});
    return page.locator('#stats').textContent();
}

// Two PNGs of one size compared in the page (no PNG library needed here): PSNR over RGB,
// the pixels that differ at all and those apart by more than 24 of 255 in a channel, and
// `blockPsnr`, the PSNR of the images' means over blocks of 4 x 4 pixels: what the eye
// integrates, where a field of sub-pixel points stands for shapes at other pixels.
export async function imageDifference(page, a, b) {
    return page.evaluate(
        async ({ a, b }) => {
            const decode = async (base64) => {
                const bitmap = await createImageBitmap(await (await fetch(`data:image/png;base64,${base64}`)).blob());
                const context = new OffscreenCanvas(bitmap.width, bitmap.height).getContext('2d');
                context.drawImage(bitmap, 0, 0);
                return { data: context.getImageData(0, 0, bitmap.width, bitmap.height).data, width: bitmap.width };
            };
            const [{ data: pa, width }, { data: pb }] = [await decode(a), await decode(b)];
            const psnrOf = (se, samples) => (se === 0 ? Infinity : 10 * Math.log10((255 * 255) / (se / samples)));
            // Per block of 4 x 4 (the last row and column of partial blocks left out), RGB sums.
            const blocks = (p) => {
                const across = Math.floor(width / 4), down = Math.floor(p.length / 4 / width / 4);
                const sums = new Float64Array(3 * across * down);
                for (let y = 0; y < 4 * down; ++y)
                    for (let x = 0; x < 4 * across; ++x)
                        for (let k = 0; k < 3; ++k) sums[3 * (Math.floor(y / 4) * across + Math.floor(x / 4)) + k] += p[4 * (y * width + x) + k];
                return sums;
            };
            const [ba, bb] = [blocks(pa), blocks(pb)];
            let blockSe = 0;
            for (let i = 0; i < ba.length; ++i) blockSe += ((ba[i] - bb[i]) / 16) ** 2;
            let se = 0, different = 0, apart = 0;
            for (let i = 0; i < pa.length; i += 4) {
                let most = 0;
                for (let k = 0; k < 3; ++k) {
                    se += (pa[i + k] - pb[i + k]) ** 2;
                    most = Math.max(most, Math.abs(pa[i + k] - pb[i + k]));
                }
                different += most > 0;
                apart += most > 24;
            }
            const pixels = pa.length / 4;
            return { psnr: psnrOf(se, 3 * pixels), blockPsnr: psnrOf(blockSe, ba.length), different, apart, pixels };
        },
        { a: a.toString('base64'), b: b.toString('base64') },
    );
}

// What ctest gives a browser test: the hexlod executable, the configs folder (grammars,
// species) and the folder for screenshots.
export const testBinary = process.env.HEXLOD_BINARY;
export const configsDir = process.env.HEXLOD_CONFIGS_DIR ?? path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..', 'configs');
export const artifactsDir = process.env.HEXLOD_WEB_ARTIFACTS ?? path.join(os.tmpdir(), 'hexlod-web-artifacts');

// A scene config of blocks of residential houses, no trees, the shipped LOD budget, for tests
// that need only houses: `count` of them with `floors` [min, max] storeys in cells of
// `cellSize` metres.
export function housesScene({ name, seed, cellSize, count, floors }) {
    return {
        name, seed, cell_size: cellSize,
        grammars: { residential: { file: path.join(configsDir, 'grammars', 'residential.grammar') } },
        buildings: [{ source: 'procedural', count, block_size: 50, street_width: 10,
            districts: [{ grammar: 'residential', share: 1, floors, lot: [14, 16] }] }],
        lod: { max_screen_space_error: 2, hysteresis: 0.2, geometric_error: [16, 4, 1, 0.25, 0] },
    };
}

// A scene config of `houses` residential houses on blocks of 60 m, `parkShare` of the blocks
// parks, and `trees` trees of the shipped species, with a tree error of 1 m: for the tree tests.
export function parkScene({ name, seed, cellSize, houses, parkShare, trees }) {
    return {
        name, seed, cell_size: cellSize,
        grammars: { residential: { file: path.join(configsDir, 'grammars', 'residential.grammar') } },
        buildings: [{ source: 'procedural', count: houses, block_size: 60, street_width: 12, park_share: parkShare,
            districts: [{ grammar: 'residential', share: 1, floors: [2, 3], lot: [16, 18] }] }],
        trees: { count: trees, species: path.join(configsDir, 'species.json') },
        lod: { max_screen_space_error: 2, hysteresis: 0.2, geometric_error: [16, 4, 1, 0.25, 0], tree_geometric_error: 1 },
    };
}

// A browser test on a scene of its own (`scene`, a scene config object): written into a fresh
// folder, served by `hexlod serve` with small impostors baked into a store in that folder (a
// quick bake that leaves nothing behind), chromium opened at `viewport`, and
// `body({base, page, pageErrors})` run; then both are closed and the folder removed.
export async function withServedScene(scene, { impostorGrid, viewport }, body) {
    if (!testBinary) throw new Error('HEXLOD_BINARY must name the hexlod executable (ctest sets it)');
    fs.mkdirSync(artifactsDir, { recursive: true });
    const folder = fs.mkdtempSync(path.join(os.tmpdir(), 'hexlod-browser-'));
    const file = path.join(folder, 'scene.json');
    fs.writeFileSync(file, JSON.stringify(scene, null, 1));
    const server = startServer(testBinary, file, [
        '--impostor-store', path.join(folder, 'impostors'), '--impostor-grid', String(impostorGrid), '--impostor-res', '16',
    ]);
    let browser;
    try {
        const base = await server.url;
        browser = await launchChromium(viewport);
        const pageErrors = [];
        browser.page.on('pageerror', (e) => pageErrors.push(e.message));
        return await body({ base, page: browser.page, pageErrors });
    } finally {
        await browser?.close();
        server.stop();
        fs.rmSync(folder, { recursive: true, force: true });
    }
}
