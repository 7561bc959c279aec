// Bundles the viewer (src/main.js and what it imports: three.js, fzstd) into dist/ with
// esbuild, next to index.html and style.css, so that everything the page loads comes from
// `hexlod serve` and nothing from a CDN. `node build.mjs` (the CMake target `web` runs it).
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
if (!fs.existsSync(path.join(here, 'node_modules', 'esbuild')) || !fs.existsSync(path.join(here, 'node_modules', 'three'))) {
    console.error('web/build.mjs: the npm packages of web/ are not installed: run scripts/install-deps.sh (npm ci in web/)');
    process.exit(1);
}
const esbuild = await import('esbuild');
const dist = path.join(here, 'dist');
fs.mkdirSync(dist, { recursive: true });
const result = await esbuild.build({
    entryPoints: [path.join(here, 'src', 'main.js')],
    bundle: true,
    format: 'esm',
    target: 'es2020',
    minify: true,
    sourcemap: true,
    outfile: path.join(dist, 'viewer.js'),
    metafile: true,
    logLevel: 'warning',
});
for (const file of ['index.html', 'style.css']) fs.copyFileSync(path.join(here, file), path.join(dist, file));
const bytes = Object.values(result.metafile.outputs).reduce((sum, o) => sum + o.bytes, 0);
console.log(`web/build.mjs: dist/viewer.js and its map, ${(bytes / 1024).toFixed(0)} KiB`);
