// What the browser test and the walk benchmark share: `hexlod serve` as a child process (its
// printed URL parsed) and Debian's chromium under playwright-core with a fresh profile.
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
