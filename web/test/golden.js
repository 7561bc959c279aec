// Test inputs: the golden byte arrays pinned by the C++ codec tests (read from their sources, so
// both languages test the very same bytes) and the payloads that `web_golden_payloads` wrote
// with the C++ encoders into $HEXLOD_WEB_GOLDEN (ctest sets it; the fixture web.golden_payloads
// runs first).
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');

export function cppGoldenBytes(testFile) {
    const source = fs.readFileSync(path.join(root, 'tests', 'grammar', testFile), 'utf8');
    const block = source.split('kGolden = {')[1].split('};')[0];
    return Uint8Array.from([...block.matchAll(/0x([0-9a-f]{2})/g)].map((m) => parseInt(m[1], 16)));
}

export function goldenFolder() {
    const folder = process.env.HEXLOD_WEB_GOLDEN;
    if (!folder) throw new Error('HEXLOD_WEB_GOLDEN is not set: run through ctest (web.decoders), which writes the payloads first');
    return folder;
}

export function goldenPayload(name) {
    const folder = goldenFolder();
    return {
        bytes: new Uint8Array(fs.readFileSync(path.join(folder, name))),
        expected: JSON.parse(fs.readFileSync(path.join(folder, `${name}.json`), 'utf8')),
    };
}

export function goldenJson(name) {
    return JSON.parse(fs.readFileSync(path.join(goldenFolder(), name), 'utf8'));
}
