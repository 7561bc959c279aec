// Validates glTF files with the Khronos glTF validator and fails on any error.
//   node tests/gltf/validate.mjs FILE... [--max-warnings N] [--served-meshes URL]
// --served-meshes: also every terminal mesh a running `hexlod serve` at URL lists in
// /api/v1/scene (each shape's mesh_url), fetched over HTTP.
// Prints one summary line per file and every error (and warning) message with its pointer.
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import validator from 'gltf-validator';

const args = process.argv.slice(2);
let maxWarnings = Infinity;
const files = [];
const served = [];
for (let i = 0; i < args.length; ++i) {
    if (args[i] === '--max-warnings') maxWarnings = Number(args[++i]);
    else if (args[i] === '--served-meshes') served.push(args[++i]);
    else files.push(args[i]);
}

// [name, bytes] of every file to validate.
const inputs = [];
for (const file of files) inputs.push([file, new Uint8Array(await readFile(file))]);
for (const base of served) {
    const scene = await (await fetch(new URL('/api/v1/scene', base))).json();
    const urls = new Set();
    for (const grammar of scene.grammars) for (const shape of grammar.shapes) if (shape.mesh_url) urls.add(shape.mesh_url);
    if (urls.size === 0) {
        console.error(`${base}: the scene lists no terminal meshes`);
        process.exit(1);
    }
    for (const url of urls) {
        const reply = await fetch(new URL(url, base));
        if (!reply.ok) {
            console.error(`${url}: HTTP ${reply.status}`);
            process.exit(1);
        }
        inputs.push([url, new Uint8Array(await reply.arrayBuffer())]);
    }
}
if (inputs.length === 0) {
    console.error('usage: validate.mjs FILE... [--max-warnings N] [--served-meshes URL]');
    process.exit(2);
}

let failed = 0;
for (const [file, data] of inputs) {
    const report = await validator.validateBytes(data, {
        uri: file,
        maxIssues: 1000,
        externalResourceFunction: (uri) =>
            readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
    });
    const { numErrors, numWarnings, numInfos, numHints } = report.issues;
    console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos, ${numHints} hints`);
    for (const m of report.issues.messages) {
        if (m.severity <= 1) console.log(`  ${m.severity === 0 ? 'error' : 'warning'} ${m.code} ${m.pointer ?? ''}: ${m.message}`);
    }
    if (numErrors > 0 || numWarnings > maxWarnings) failed++;
}
process.exit(failed ? 1 : 0);
