// Validates glTF files with the Khronos glTF validator and fails on any error.
//   node tests/gltf/validate.mjs FILE... [--max-warnings N]
// Prints one summary line per file and every error (and warning) message with its pointer.
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import validator from 'gltf-validator';

const args = process.argv.slice(2);
let maxWarnings = Infinity;
const files = [];
for (let i = 0; i < args.length; ++i) {
    if (args[i] === '--max-warnings') maxWarnings = Number(args[++i]);
    else files.push(args[i]);
}
if (files.length === 0) {
    console.error('usage: validate.mjs FILE... [--max-warnings N]');
    process.exit(2);
}

let failed = 0;
for (const file of files) {
    const data = new Uint8Array(await readFile(file));
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
