// Terminal set, version 1 (docs/protocol.md): the 92-byte header, the counts per shape and the
// zstd body of eight u32 columns (positions and building ids delta + zigzag, the shape word
// XORed with its run's shape id), decoded back into 32-byte records exactly as
// grammar/src/terminal_set_codec.cpp does, with the same validation: a payload this rejects,
// the C++ decoder rejects too, and the other way round.
import { hex64 } from './checksum64.js';
import { MAX_DECODED_BYTES, openPayload, readU64, u64Number, unzigzagInPlace, verifyChecksum } from './format.js';
import { PayloadError } from './payload_error.js';
import { decompressFrame } from './zstd_frame.js';

export const TERMINAL_SET_VERSION = 1;
export const TERMINAL_HEADER_BYTES = 92;
const MAX_RECORDS = 2 ** 27;
const MAX_SHAPES = 65536;

export function decodeTerminalSet(payload) {
    const { bytes, view } = openPayload(payload, TERMINAL_HEADER_BYTES, 'HXT1', 'a terminal set', TERMINAL_SET_VERSION);
    const count = u64Number(readU64(view, 72));
    const bodyBytes = u64Number(readU64(view, 80));
    const shapes = view.getUint32(88, true);
    if (count > MAX_RECORDS) throw new PayloadError(`record count ${count} exceeds the limit`);
    if (shapes > MAX_SHAPES) throw new PayloadError(`shape count ${shapes} exceeds 65536`);
    const countsEnd = TERMINAL_HEADER_BYTES + 4 * shapes;
    if (bytes.length < countsEnd || bytes.length - countsEnd < bodyBytes)
        throw new PayloadError(`truncated: ${bytes.length} bytes, the header needs ${countsEnd + bodyBytes}`);
    if (bytes.length - countsEnd > bodyBytes) throw new PayloadError('trailing bytes after the body');
    const countPerShape = new Uint32Array(shapes);
    let total = 0;
    for (let s = 0; s < shapes; ++s) total += countPerShape[s] = view.getUint32(TERMINAL_HEADER_BYTES + 4 * s, true);
    if (total !== count)
        throw new PayloadError(`counts per shape sum to ${total}, the header says ${count} records`);
    if (32 * count > MAX_DECODED_BYTES)
        throw new PayloadError(`${count} records are more than this viewer decodes in one batch`);
    const body = decompressFrame(bytes.subarray(countsEnd), 32 * count);
    const checksum = verifyChecksum(bytes, countsEnd, body);

    // Columns to records: the body's word c of record i is at c * n + i.
    const n = count;
    const columns = new Uint32Array(body.buffer, body.byteOffset, 8 * n).slice();
    for (let c = 0; c < 4; ++c) unzigzagInPlace(columns.subarray(c * n, (c + 1) * n));
    const records = new Uint32Array(8 * n);
    let shape = 0, endOfRun = shapes === 0 ? n : countPerShape[0];
    for (let i = 0; i < n; ++i) {
        while (i >= endOfRun) endOfRun += countPerShape[++shape];
        const last = columns[7 * n + i];
        if ((last & 0xffff) !== 0) throw new PayloadError(`record ${i} lies outside the run of its shape`);
        for (let c = 0; c < 7; ++c) records[8 * i + c] = columns[c * n + i];
        records[8 * i + 7] = (last ^ shape) >>> 0;
    }
    return {
        kind: 'terminal-set',
        version: TERMINAL_SET_VERSION,
        checksum,
        cell: { q: view.getInt32(16, true), r: view.getInt32(20, true) },
        grammar: view.getUint32(24, true),
        reserved: view.getUint32(28, true),
        grammarHash: hex64(readU64(view, 32)),
        key: hex64(readU64(view, 40)),
        origin: [view.getFloat64(48, true), view.getFloat64(56, true), view.getFloat64(64, true)],
        count: n,
        countPerShape,
        records, // 8 u32 words per record, the std430 layout of grammar/terminal_set.h
        positions: new Float32Array(records.buffer), // the same words read as floats
        byteSize: records.byteLength + countPerShape.byteLength,
    };
}
