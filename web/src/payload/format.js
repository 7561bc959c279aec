// What both payload formats share (docs/protocol.md): the little-endian header reads, the
// magic and version check, the checksum over the covered header and the body, and the delta +
// zigzag columns.
import { checksum64, hex64 } from './checksum64.js';
import { PayloadError } from './payload_error.js';

// A viewer-side cap on one decoded body: the format allows 4 GiB, a browser tab does not.
export const MAX_DECODED_BYTES = 512 * 1024 * 1024;

export function asBytes(payload) {
    if (payload instanceof Uint8Array) return payload;
    if (payload instanceof ArrayBuffer) return new Uint8Array(payload);
    throw new PayloadError('payload must be an ArrayBuffer or a Uint8Array');
}

export function readU64(view, at) {
    return [view.getUint32(at + 4, true), view.getUint32(at, true)];
}

// A u64 count as a Number, or Infinity when it is beyond 2^53 (every limit is far below).
export function u64Number([h, l]) {
    return h >= 0x200000 ? Infinity : h * 4294967296 + l;
}

// The payload's bytes and a DataView on them, after the size, magic and version checks.
export function openPayload(payload, headerBytes, magic, what, version) {
    const bytes = asBytes(payload);
    if (bytes.length < headerBytes) throw new PayloadError(`truncated header: ${bytes.length} of ${headerBytes} bytes`);
    for (let i = 0; i < 4; ++i)
        if (bytes[i] !== magic.charCodeAt(i)) throw new PayloadError(`not ${what} (bad magic)`);
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    const found = view.getUint32(4, true);
    if (found !== version)
        throw new PayloadError(`unsupported ${what.replace(/^an? /, '')} version ${found} (this viewer reads ${version})`);
    return { bytes, view };
}

export function verifyChecksum(bytes, coveredEnd, body) {
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    const stored = readU64(view, 8);
    const computed = checksum64(body, checksum64(bytes.subarray(16, coveredEnd)));
    if (computed[0] !== stored[0] || computed[1] !== stored[1]) throw new PayloadError('checksum mismatch');
    return hex64(stored);
}

export function unzigzagInPlace(column) {
    let previous = 0;
    for (let i = 0; i < column.length; ++i) {
        const z = column[i];
        previous = (previous + ((z >>> 1) ^ -(z & 1))) >>> 0;
        column[i] = previous;
    }
}
